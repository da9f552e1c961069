//! The memory report: bytes of every voxel texture and radiance volume a renderer allocates
//! for its grid, beside what the same textures take over the bounding cube of the grid's
//! longest axis (a dense cube, the layout a fitted grid is measured against). The report is how
//! the memory a layout and a storage save is measured (docs/design/storage.md).

use std::fmt;

use super::radiance::{Chains, RadianceDescs};
use crate::gpu::ImageDesc;
use crate::voxel::bricks;
use crate::voxel::volume::{extent_of, voxel_desc, VOXEL_TEXTURES};
use crate::voxel::VoxelGrid;

/// What decides a renderer's allocations besides its grid.
#[derive(Clone, Copy, Debug)]
pub struct Layout<'a> {
    /// The voxel-space bounce target.
    pub bounces: bool,
    /// The mip levels' lists of occupied texels.
    pub listed: bool,
    /// Brick-pool slots (the empty one included) of sparse storage; `None`: dense or resident.
    pub pool: Option<u32>,
    /// Resident storage: the bricks whose blocks are bound.
    pub resident: Option<&'a bricks::Residency>,
    /// A full-size history for temporal filtering.
    pub temporal: bool,
    /// The sampled chains above level 0.
    pub chains: Chains,
}

/// One texture or buffer.
#[derive(Clone, Debug, serde::Serialize)]
pub struct MemoryRow {
    pub name: &'static str,
    /// Texels along x, y, z at level 0 (a buffer: its length in bytes, 1, 1).
    pub extent: [u32; 3],
    pub mips: u32,
    /// Bytes at this grid.
    pub bytes: u64,
    /// Bytes over the dense N³ cube (N the longest axis; a clipmap's finest voxels over its
    /// coarsest level).
    pub cube_bytes: u64,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct MemoryReport {
    pub dims: [u32; 3],
    /// The side of the cube the cube column is over.
    pub cube_side: u32,
    pub rows: Vec<MemoryRow>,
    pub bytes: u64,
    pub cube_bytes: u64,
}

impl MemoryReport {
    /// What a renderer allocates at `grid` in `layout`: the voxel textures, the radiance
    /// volumes, the page table and the occupied-voxel lists. The cube column is the dense
    /// layout over the bounding cube.
    pub fn for_grid(grid: &VoxelGrid, layout: &Layout) -> Self {
        let Layout { bounces, listed, pool, resident, temporal, chains } = *layout;
        let stored = pool.map_or(extent_of(grid.dims), bricks::pool_extent);
        // The same textures, dense, over the bounding cube of the grid's longest axis; for a
        // clipmap, one grid of its finest voxels over its coarsest level's extent.
        let side = grid.clip.map_or(grid.longest(), |c| c.res << (c.levels - 1));
        let cube = VoxelGrid { dims: glam::UVec3::splat(side), clip: None, ..*grid };
        let named = |grid: &VoxelGrid, extent| {
            let voxel = voxel_desc(extent);
            let mut v: Vec<(&'static str, ImageDesc, bool)> =
                VOXEL_TEXTURES.iter().map(|&n| (n, voxel, true)).collect();
            v.extend(RadianceDescs::new(grid, bounces, extent, temporal, chains).named());
            v
        };
        // A resident per-voxel texture holds the blocks bound to it.
        let bytes = |d: &ImageDesc, per_voxel: bool| match resident {
            Some(r) if per_voxel => r.bound_bytes(grid.dims, d.format),
            _ => d.texel_bytes(),
        };
        let mut rows: Vec<MemoryRow> = named(grid, stored)
            .into_iter()
            .zip(named(&cube, extent_of(cube.dims)))
            .map(|((name, d, per_voxel), (_, cube, _))| MemoryRow {
                name,
                extent: d.size(),
                mips: d.mip_levels,
                bytes: bytes(&d, per_voxel),
                cube_bytes: cube.texel_bytes(),
            })
            .collect();
        if pool.is_some() || resident.is_some() {
            let table = bricks::table_bytes(grid);
            rows.push(MemoryRow {
                name: "brick page table",
                extent: [table as u32, 1, 1],
                mips: 1,
                bytes: table,
                cube_bytes: 0,
            });
        }
        let list = crate::voxel::occupied::list_bytes;
        let room = match (pool, resident) {
            (Some(p), _) => bricks::voxel_room(grid, p),
            (None, Some(r)) => r.voxel_room(),
            (None, None) => grid.voxel_count() as u64,
        };
        let occupied = list(room);
        if listed {
            let bricks = pool.map(|p| p.saturating_sub(1) as u64).or(resident.map(|r| r.bricks.len() as u64));
            let parents = super::occupancy::parent_list_bytes(grid.dims.into(), grid.mip_levels(), bricks);
            let n = side;
            rows.push(MemoryRow {
                name: "occupied texel lists (mips)",
                extent: [parents as u32, 1, 1],
                mips: 1,
                bytes: parents,
                cube_bytes: super::occupancy::parent_list_bytes([n; 3], 32 - n.leading_zeros(), None),
            });
        }
        rows.push(MemoryRow {
            name: "occupied voxel list",
            extent: [occupied as u32, 1, 1],
            mips: 1,
            bytes: occupied,
            cube_bytes: list((side as u64).pow(3)),
        });
        MemoryReport {
            dims: grid.dims.into(),
            cube_side: side,
            bytes: rows.iter().map(|r| r.bytes).sum(),
            cube_bytes: rows.iter().map(|r| r.cube_bytes).sum(),
            rows,
        }
    }

    /// The total in MiB.
    pub fn mib(&self) -> f64 {
        self.bytes as f64 / 1048576.0
    }

    pub fn cube_mib(&self) -> f64 {
        self.cube_bytes as f64 / 1048576.0
    }
}

impl fmt::Display for MemoryReport {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let [x, y, z] = self.dims;
        let n = self.cube_side;
        let mib = |b: u64| b as f64 / 1048576.0;
        writeln!(
            f,
            "{:<30} {:>15} {:>4} {:>10} {:>12}",
            "GPU memory",
            "extent",
            "mips",
            "MiB",
            format!("MiB at {n}³")
        )?;
        for r in &self.rows {
            let e = format!("{}×{}×{}", r.extent[0], r.extent[1], r.extent[2]);
            writeln!(f, "{:<30} {:>15} {:>4} {:>10.1} {:>12.1}", r.name, e, r.mips, mib(r.bytes), mib(r.cube_bytes))?;
        }
        write!(
            f,
            "{:<30} {:>15} {:>4} {:>10.1} {:>12.1}   ({:.0}% of the cube)",
            "total",
            format!("{x}×{y}×{z}"),
            "",
            self.mib(),
            self.cube_mib(),
            100.0 * self.bytes as f64 / self.cube_bytes.max(1) as f64
        )
    }
}
