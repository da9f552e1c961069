//! The `.binvox` occupancy format (Patrick Min's binvox): an ASCII header giving `dim`,
//! `translate` and `scale` of the grid, then run-length pairs (value, count ≤ 255) over the
//! voxels in x-z-y order (y fastest, then z, then x).

use std::io::{BufRead, Write};
use std::path::Path;

use glam::Vec3;

use super::VoxelGrid;
use crate::error::{Error, Result};

/// Voxel index in binvox order for (x, y, z).
fn binvox_index(n: usize, x: usize, y: usize, z: usize) -> usize {
    x * n * n + z * n + y
}

/// Writes `occupied` (indexed by [`VoxelGrid::index`]) as a binvox file.
pub fn write(path: &Path, grid: &VoxelGrid, occupied: &[bool]) -> Result<()> {
    let n = grid.resolution as usize;
    let mut ordered = vec![false; n * n * n];
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                ordered[binvox_index(n, x, y, z)] = occupied[grid.index(x as u32, y as u32, z as u32)];
            }
        }
    }
    let mut out = Vec::new();
    let o = grid.origin;
    write!(
        out,
        "#binvox 1\ndim {n} {n} {n}\ntranslate {} {} {}\nscale {}\ndata\n",
        o.x,
        o.y,
        o.z,
        grid.voxel * n as f32
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
                if d.len() != 3 || d[0] != d[1] || d[1] != d[2] || d[0] < 1.0 {
                    return Err(bad("vct reads cubic grids only"));
                }
                dim = Some(d[0] as u32);
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
    let n = dim.ok_or_else(|| bad("missing dim"))? as usize;
    let grid = VoxelGrid { origin: translate, voxel: scale / n as f32, resolution: n as u32 };
    let data = &bytes[cursor.position() as usize..];
    let mut ordered = Vec::with_capacity(n * n * n);
    for pair in data.chunks_exact(2) {
        ordered.extend(std::iter::repeat_n(pair[0] != 0, pair[1] as usize));
    }
    if ordered.len() != n * n * n {
        return Err(bad(&format!("{} voxels of data for a {n}³ grid", ordered.len())));
    }
    let mut occupied = vec![false; n * n * n];
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                occupied[grid.index(x as u32, y as u32, z as u32)] = ordered[binvox_index(n, x, y, z)];
            }
        }
    }
    Ok((grid, occupied))
}
