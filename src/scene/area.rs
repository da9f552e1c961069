//! Emissive quads as area lights. A material whose emitting triangles all pair into planar
//! parallelograms (two triangles sharing a diagonal, as an OBJ quad or a glTF rectangle
//! loads) lights the scene through one `Light::Area` per quad: direct light from the
//! polygon's exact irradiance (Lambert's formula for a polygon, in Arvo 1995's vector form,
//! clipped to the receiver's horizon: common/light.glsl), shadowed by a cube map from the quad's
//! centre and injected into the voxels like any light. The quad keeps its emission for the eye
//! and for the path tracer (which samples the triangles themselves), but its voxels do not
//! emit it: a partly covered voxel would hold the quad's full radiance at full opacity, so the
//! first gather would see a 0.47 m quad as a blotchy texel-sized lamp (docs/design/injection.md).
//! Other emitters (single triangles, curved or textured ones) stay voxel emitters.

use glam::Vec3;

use super::{Light, Mesh, Scene, MAX_LIGHTS};

/// Emitting side: the quads' winding (counter-clockwise seen from the lit side, as OBJ and glTF
/// define the front face). The emitter emits from its front face only: the path tracer's
/// triangles emit from both, and what the classic Cornell box's quad sends up lights the 1 cm
/// gap under the ceiling, not the room.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    pub center: Vec3,
    /// Half edges: corners `center ± half_u ± half_v`; `half_u × half_v` points to the lit side.
    pub half_u: Vec3,
    pub half_v: Vec3,
}

/// The parallelogram two triangles make when they share an edge that is its diagonal, with
/// the same winding; `eps` the distance under which points coincide.
fn pair(a: [Vec3; 3], b: [Vec3; 3], eps: f32) -> Option<Quad> {
    let same = |p: Vec3, q: Vec3| p.distance_squared(q) <= eps * eps;
    for i in 0..3 {
        // a's edge (a[i], a[i+1]) against b's edge (b[j+1], b[j]) (opposite direction: same winding).
        let (e0, e1, x) = (a[i], a[(i + 1) % 3], a[(i + 2) % 3]);
        for j in 0..3 {
            let (f0, f1, y) = (b[j], b[(j + 1) % 3], b[(j + 2) % 3]);
            if !(same(e0, f1) && same(e1, f0)) {
                continue;
            }
            // A parallelogram: the diagonals bisect each other.
            if !same(x + y, e0 + e1) {
                return None;
            }
            let normal = (e1 - e0).cross(x - e0);
            if normal.length() <= eps * eps {
                return None;
            }
            // Corners x, e0, y, e1: x's two sides give the half edges (centre - u - v = x,
            // centre + u + v = y, as x + y = e0 + e1).
            let center = 0.5 * (x + y);
            let (mut half_u, mut half_v) = (0.5 * (e0 - x), 0.5 * (e1 - x));
            if half_u.cross(half_v).dot(normal) < 0.0 {
                std::mem::swap(&mut half_u, &mut half_v);
            }
            return Some(Quad { center, half_u, half_v });
        }
    }
    None
}

/// Each emitting material's quads, or `None` for a material whose emitting triangles do not all
/// pair into parallelograms (it stays a voxel emitter).
fn material_quads(mesh: &Mesh, material: u32, eps: f32) -> Option<Vec<Quad>> {
    let tris: Vec<[Vec3; 3]> = mesh
        .draws
        .iter()
        .filter(|d| d.material == material)
        .flat_map(|d| (d.first_index / 3..(d.first_index + d.index_count) / 3).map(|t| mesh.triangle(t as usize)))
        .collect();
    if tris.is_empty() || !tris.len().is_multiple_of(2) || tris.len() > 2 * MAX_LIGHTS {
        return None;
    }
    let mut used = vec![false; tris.len()];
    let mut quads = Vec::new();
    for i in 0..tris.len() {
        if used[i] {
            continue;
        }
        let (j, q) =
            (i + 1..tris.len()).filter(|&j| !used[j]).find_map(|j| pair(tris[i], tris[j], eps).map(|q| (j, q)))?;
        used[i] = true;
        used[j] = true;
        quads.push(q);
    }
    Some(quads)
}

/// Turns the scene's emissive quads into area lights while lights remain (MAX_LIGHTS in all),
/// marking their materials [`Material::area_light`]. A material's quads convert all together or
/// not at all. Returns how many lights were added.
pub fn add_area_lights(scene: &mut Scene) -> usize {
    let eps = 1e-5 * scene.mesh.bounds.size().length().max(1e-6);
    let mut added = 0;
    for (m, material) in scene.materials.iter_mut().enumerate() {
        if material.emissive.max_element() <= 0.0 || material.area_light {
            continue;
        }
        let Some(quads) = material_quads(&scene.mesh, m as u32, eps) else { continue };
        if scene.lights.len() + quads.len() > MAX_LIGHTS {
            continue;
        }
        scene.lights.extend(quads.iter().map(|q| Light::Area {
            center: q.center,
            half_u: q.half_u,
            half_v: q.half_v,
            radiance: material.emissive,
        }));
        material.area_light = true;
        added += quads.len();
    }
    added
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_triangles_of_a_quad_pair_into_its_parallelogram() {
        let (a, b, c, d) = (Vec3::ZERO, Vec3::X, Vec3::new(1.0, 0.0, -1.0), Vec3::NEG_Z);
        // Fan triangulation (a, b, c), (a, c, d): counter-clockwise seen from +y.
        let q = pair([a, b, c], [a, c, d], 1e-6).expect("a quad");
        assert!((q.center - Vec3::new(0.5, 0.0, -0.5)).length() < 1e-6);
        assert!(q.half_u.cross(q.half_v).normalize().dot(Vec3::Y) > 0.999, "lit side +y: {q:?}");
        let corners = [q.center - q.half_u - q.half_v, q.center + q.half_u + q.half_v];
        for p in corners {
            assert!([a, b, c, d].iter().any(|k| k.distance(p) < 1e-6), "{p} is no corner");
        }
        // A triangle pair that is no parallelogram (a kite), or wound differently, is none.
        assert!(pair([a, b, c], [a, c, Vec3::new(-0.5, 0.0, -2.0)], 1e-6).is_none());
        assert!(pair([a, b, c], [a, d, c], 1e-6).is_none());
    }

    const OBJ: &str = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nv 0 1 0\nv 1 1 0\nv 0 1 -1\n\
        usemtl light\nf 1 2 3 4\nusemtl glow\nf 5 6 7\n";
    const MTL: &str = "newmtl light\nKd 0.5 0.5 0.5\nKe 4 4 4\nnewmtl glow\nKd 0.5 0.5 0.5\nKe 1 0 0\n";

    fn load(gi: &str) -> Scene {
        let toml = format!("mesh = \"m.obj\"\n{gi}");
        let files: [(&str, &[u8]); 3] =
            [("s.toml", toml.as_bytes()), ("m.obj", OBJ.as_bytes()), ("m.mtl", MTL.as_bytes())];
        crate::scene::load_from_memory(&files, "s.toml").unwrap()
    }

    #[test]
    fn an_emissive_quad_loads_as_an_area_light_and_a_lone_triangle_stays_a_voxel_emitter() {
        let scene = load("");
        let areas: Vec<&Light> = scene.lights.iter().filter(|l| l.is_mesh_emitter()).collect();
        assert_eq!(areas.len(), 1, "{:?}", scene.lights);
        let Light::Area { center, half_u, half_v, radiance } = *areas[0] else { unreachable!() };
        assert!((center - Vec3::new(0.5, 0.0, -0.5)).length() < 1e-6);
        assert!((half_u.length() - 0.5).abs() < 1e-6 && (half_v.length() - 0.5).abs() < 1e-6);
        assert_eq!(radiance, Vec3::splat(4.0));
        let by_name = |n: &str| scene.materials.iter().find(|m| m.name == n).unwrap();
        assert!(by_name("light").area_light && !by_name("glow").area_light);
        // Switched off, the quad emits through its voxels.
        let off = load("[gi]\narea_lights = false\n");
        assert!(off.lights.iter().all(|l| !l.is_mesh_emitter()) && !off.materials.iter().any(|m| m.area_light));
    }
}
