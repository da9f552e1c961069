//! The `.binvox` occupancy format (Patrick Min's binvox): an ASCII header giving `dim` (voxels
//! along x, y and z, as binvox-rw writes them), `translate` and `scale` (the longest axis' world
//! length) of the grid, then run-length pairs (value, count ≤ 255) over the voxels in x-z-y
//! order (y fastest, then z, then x).

use std::io::{BufRead, Write};
use std::path::Path;

use glam::Vec3;

use super::VoxelGrid;
use crate::error::{Error, Result};

/// Voxel index in binvox order for (x, y, z) in a grid of `d` voxels.
fn binvox_index(d: [usize; 3], x: usize, y: usize, z: usize) -> usize {
    (x * d[2] + z) * d[1] + y
}

/// Visits every voxel of a grid of `d` voxels.
fn each_voxel(d: [usize; 3], mut f: impl FnMut(usize, usize, usize)) {
    for z in 0..d[2] {
        for y in 0..d[1] {
            for x in 0..d[0] {
                f(x, y, z);
            }
        }
    }
}

/// Writes `occupied` (indexed by [`VoxelGrid::index`]) as a binvox file.
pub fn write(path: &Path, grid: &VoxelGrid, occupied: &[bool]) -> Result<()> {
    let d = grid.dims.to_array().map(|v| v as usize);
    let mut ordered = vec![false; grid.voxel_count()];
    each_voxel(d, |x, y, z| ordered[binvox_index(d, x, y, z)] = occupied[grid.index(x as u32, y as u32, z as u32)]);
    let mut out = Vec::new();
    let o = grid.origin;
    write!(
        out,
        "#binvox 1\ndim {} {} {}\ntranslate {} {} {}\nscale {}\ndata\n",
        d[0],
        d[1],
        d[2],
        o.x,
        o.y,
        o.z,
        grid.voxel * grid.longest() as f32
    )
    .expect("writing to memory");
    let mut i = 0;
    while i < ordered.len() {
        let v = ordered[i];
        let mut run = 1;
        while run < 255 && i + run < ordered.len() && ordered[i + run] == v {
            run += 1;
        }
        out.push(v as u8);
        out.push(run as u8);
        i += run;
    }
    std::fs::write(path, out).map_err(|source| Error::Io { path: path.to_path_buf(), source })
}

/// Reads a binvox file back: the grid it describes and occupancy in [`VoxelGrid::index`] order.
pub fn read(path: &Path) -> Result<(VoxelGrid, Vec<bool>)> {
    let bad = |m: &str| Error::input(path, format!("not a binvox file: {m}"));
    let bytes = std::fs::read(path).map_err(|source| Error::Io { path: path.to_path_buf(), source })?;
    let mut cursor = std::io::Cursor::new(&bytes);
    let (mut dim, mut translate, mut scale) = (None, Vec3::ZERO, 1.0f32);
    let mut line = String::new();
    loop {
        line.clear();
        if cursor.read_line(&mut line).map_err(|_| bad("unreadable header"))? == 0 {
            return Err(bad("no data section"));
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let nums = |w: &[&str]| w.iter().map(|s| s.parse::<f32>()).collect::<Result<Vec<_>, _>>();
        match words.first().copied() {
            Some("#binvox") => {}
            Some("dim") => {
                let d = nums(&words[1..]).map_err(|_| bad("bad dim"))?;
                if d.len() != 3 || d.iter().any(|&v| !(1.0..=4096.0).contains(&v) || v.fract() != 0.0) {
                    return Err(bad("dim must be three whole numbers in 1..=4096"));
                }
                dim = Some([d[0] as usize, d[1] as usize, d[2] as usize]);
            }
            Some("translate") => {
                let t = nums(&words[1..]).map_err(|_| bad("bad translate"))?;
                translate = Vec3::new(t[0], t[1], t[2]);
            }
            Some("scale") => scale = words.get(1).and_then(|s| s.parse().ok()).ok_or_else(|| bad("bad scale"))?,
            Some("data") => break,
            _ => return Err(bad(&format!("unexpected header line '{}'", line.trim()))),
        }
    }
    let d = dim.ok_or_else(|| bad("missing dim"))?;
    let dims = glam::UVec3::new(d[0] as u32, d[1] as u32, d[2] as u32);
    let grid = VoxelGrid {
        origin: translate,
        voxel: scale / dims.max_element() as f32,
        dims,
        warp: Default::default(),
        clip: None,
    };
    let data = &bytes[cursor.position() as usize..];
    let len = grid.voxel_count();
    let mut ordered = Vec::with_capacity(len);
    for pair in data.chunks_exact(2) {
        ordered.extend(std::iter::repeat_n(pair[0] != 0, pair[1] as usize));
        if ordered.len() > len {
            break;
        }
    }
    if ordered.len() != len {
        return Err(bad(&format!("{} voxels of data for a {} grid", ordered.len(), grid.dims_label())));
    }
    let mut occupied = vec![false; len];
    each_voxel(d, |x, y, z| occupied[grid.index(x as u32, y as u32, z as u32)] = ordered[binvox_index(d, x, y, z)]);
    Ok((grid, occupied))
}
