//! Voxel warping by a function (Freed 2018 §4.6.1): the grid's texels are spread unevenly over
//! its box, small near the camera and large far from it, so the same memory holds finer detail
//! where the view is. Each axis is mapped on its own, so a texel is still an axis-aligned box
//! in world space (of its own size), and exact coverage stays a triangle/box test.
//!
//! The thesis maps a grid fraction x ∈ [0, 1] to a texture fraction with the cubic
//! w(x) = αx + (3 − 3α)x² + (2α − 2)x³, whose slope is α at both ends and 1.5 − α/2 at the
//! centre, where its camera sits (α = 0.25 there). A fitted grid rarely has the camera at its
//! centre, so here the peak sits at the camera's fraction c of each axis: each side of c is the
//! thesis' half-cubic scaled to its length, w(x) = c·h(x/c) below c and 1 − (1 − c)·h((1 − x)/(1 − c))
//! above, with h(u) = 2·w_thesis(u/2). For c = 1/2 this is the thesis' function exactly; α = 1 is
//! no warp. Outside [0, 1] (a cone's filter reaching past the edge) the map goes on at slope α.
//!
//! The shaders' copy is `shaders-glsl/common/warp.glsl`; the exact coverage reference
//! (`reference::coverage`) inverts the map on its own, by bisection.
//!
//! [`Warp`] is the layout's choice: even texels, this function, or the perspective warp of §4.6.2
//! (`voxel::perspective`).

use glam::{DMat4, DVec3, Mat4, Vec3, Vec4};

use crate::error::{Error, Result};

/// The thesis' end slope (§4.6.1: "for our implementation, α = 0.25").
pub const THESIS_END_SLOPE: f32 = 0.25;

/// A warp as a renderer's options ask for it: which, and how strong.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WarpChoice {
    /// The thesis' function, with this slope at the grid's faces (§4.6.1).
    Function(f32),
    /// The camera's frustum, near texels this share of the far ones' width (§4.6.2).
    Perspective(f32),
}

impl WarpChoice {
    /// `warp function 0.25`, `warp perspective 0.25`: for tables and the overlay.
    pub fn label(&self) -> String {
        match self {
            WarpChoice::Function(s) => format!("warp function {s}"),
            WarpChoice::Perspective(r) => format!("warp perspective {r}"),
        }
    }
}

/// The near texels' width over the far ones' by default (the thesis' function warp's end slope).
pub const DEFAULT_RATIO: f32 = 0.25;

/// A projective map of grid fractions onto texture fractions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    /// Grid fraction (x, 1) to texture fraction times w: t = (H x).xyz / (H x).w, where w is the
    /// distance from the frustum's apex (world units).
    pub to_texel: DMat4,
    /// The inverse of `to_texel`.
    pub from_texel: DMat4,
    /// The apex's distance behind the eye, e (the near plane's w).
    pub near: f64,
    /// e / (e + D): the near texels' width over the far ones'.
    pub ratio: f32,
}

impl Perspective {
    /// The texture fraction of grid fraction `x`; `None` within half the near plane's distance
    /// of the apex or behind it (no texel lies there; the shaders clip there too).
    pub fn forward(&self, x: DVec3) -> Option<DVec3> {
        let q = self.to_texel * x.extend(1.0);
        (q.w > 0.5 * self.near).then(|| q.truncate() / q.w)
    }

    /// The grid fraction of texture fraction `t`.
    pub fn inverse(&self, t: DVec3) -> DVec3 {
        let q = self.from_texel * t.extend(1.0);
        q.truncate() / q.w
    }

    /// Texels per grid voxel at grid fraction `x`, as one size: the cube root of the map's
    /// Jacobian determinant, det H / w⁴ for a projective map.
    pub fn slope(&self, x: DVec3) -> f64 {
        let w = (self.to_texel * x.extend(1.0)).w.max(0.5 * self.near);
        (self.to_texel.determinant().abs() / w.powi(4)).cbrt()
    }

    /// Texels per grid voxel on the near plane, where they are finest.
    pub fn peak_slope(&self) -> f64 {
        (self.to_texel.determinant().abs() / self.near.powi(4)).cbrt()
    }

    /// `vec4 warp` of the shaders: the peak slope, the cube root of |det H|, the w triangles are
    /// clipped at (half the near plane's), and 0 (the perspective warp's mark).
    pub fn gpu(&self) -> Vec4 {
        Vec4::new(
            self.peak_slope() as f32,
            self.to_texel.determinant().abs().cbrt() as f32,
            (0.5 * self.near) as f32,
            0.0,
        )
    }
}

/// How a grid's texels spread over its box.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[allow(clippy::large_enum_variant)] // the perspective's two matrices; one grid per renderer, copied rarely
pub enum Warp {
    /// Evenly: texel v is the box's voxel v.
    #[default]
    None,
    /// The thesis' function (§4.6.1), each axis on its own.
    Function(Function),
    /// The camera's frustum, projectively (§4.6.2).
    Perspective(Perspective),
}

impl Warp {
    /// No warp: texels evenly spread.
    pub const NONE: Warp = Warp::None;

    /// The thesis' warp function with its peak at grid fraction `centre` (clamped into the
    /// grid) and slope `end_slope` at the faces.
    pub fn function(centre: Vec3, end_slope: f32) -> Result<Self> {
        Function::new(centre, end_slope).map(Warp::Function)
    }

    pub fn is_none(&self) -> bool {
        match self {
            Warp::None => true,
            Warp::Function(f) => f.is_none(),
            Warp::Perspective(_) => false,
        }
    }

    /// `vec4 warp` of the shaders (common/warp.glsl): the function's centre and end slope, or
    /// for the perspective warp its peak slope, the cube root of its matrix's determinant and
    /// the w it clips triangles at, with w = 0.
    pub fn gpu(&self) -> Vec4 {
        match self {
            Warp::None => Function::NONE.gpu(),
            Warp::Function(f) => f.gpu(),
            Warp::Perspective(p) => p.gpu(),
        }
    }

    /// `mat4 warp_proj` of the shaders: grid fraction to texture fraction, homogeneous (the
    /// identity but for the perspective warp).
    pub fn proj(&self) -> Mat4 {
        match self {
            Warp::Perspective(p) => p.to_texel.as_mat4(),
            _ => Mat4::IDENTITY,
        }
    }

    /// The inverse of [`Self::proj`].
    pub fn unproj(&self) -> Mat4 {
        match self {
            Warp::Perspective(p) => p.from_texel.as_mat4(),
            _ => Mat4::IDENTITY,
        }
    }

    /// The texture fraction of grid fraction `x` (outside the grid's texels where the
    /// perspective warp has none: behind its apex).
    pub fn forward3(&self, x: glam::DVec3) -> glam::DVec3 {
        match self {
            Warp::None => x,
            Warp::Function(f) => glam::DVec3::new(f.forward(x.x, 0), f.forward(x.y, 1), f.forward(x.z, 2)),
            Warp::Perspective(p) => p.forward(x).unwrap_or(glam::DVec3::splat(-4.0)),
        }
    }

    /// The grid fraction of texture fraction `t` (the inverse of [`Self::forward3`]).
    pub fn inverse3(&self, t: glam::DVec3) -> glam::DVec3 {
        match self {
            Warp::None => t,
            Warp::Function(f) => glam::DVec3::new(f.inverse(t.x, 0), f.inverse(t.y, 1), f.inverse(t.z, 2)),
            Warp::Perspective(p) => p.inverse(t),
        }
    }
}

/// A per-axis warp of the grid's box onto its texels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Function {
    /// Where the texels are smallest, as a fraction of each axis (the camera's place).
    pub centre: Vec3,
    /// The slope at the grid's faces (texels over grid fraction): 1 is no warp, below 1 the
    /// texels there are 1/α times as large as an unwarped grid's.
    pub end_slope: f32,
}

/// The half-cubic of one side: h(0) = 0, h(1) = 1, h'(0) = α, h'(1) = 1.5 − α/2, convex and
/// increasing on [0, 1] (h'' = 3(1 − α)(1 − u) ≥ 0).
fn h(u: f64, a: f64) -> f64 {
    if u <= 0.0 {
        return a * u;
    }
    u * (a + u * (1.5 - 1.5 * a + u * (0.5 * a - 0.5)))
}

fn h_slope(u: f64, a: f64) -> f64 {
    if u <= 0.0 {
        return a;
    }
    a + u * (3.0 - 3.0 * a + u * (1.5 * a - 1.5))
}

/// u with h(u) = t: Newton's method from min(1, t/a), right of the root (h(u) >= a·u), from
/// where it moves monotonically onto it, h being convex and increasing.
fn h_inverse(t: f64, a: f64) -> f64 {
    if t <= 0.0 {
        return t / a;
    }
    let mut u = (t / a).min(1.0);
    for _ in 0..40 {
        let next = u - (h(u, a) - t) / h_slope(u, a);
        if (next - u).abs() <= 1e-15 {
            return next;
        }
        u = next;
    }
    u
}

impl Function {
    /// No warp: texels evenly spread.
    pub const NONE: Function = Function { centre: Vec3::splat(0.5), end_slope: 1.0 };

    /// The thesis' warp function with its peak at grid fraction `centre` (clamped into the
    /// grid) and slope `end_slope` at the faces.
    pub fn new(centre: Vec3, end_slope: f32) -> Result<Self> {
        if !(end_slope.is_finite() && (0.05..=1.0).contains(&end_slope)) {
            return Err(Error::param(
                "warp-slope",
                format!("{end_slope} is not in 0.05..=1 (the texels' slope at the grid's faces; 1 is no warp)"),
            ));
        }
        if !centre.is_finite() {
            return Err(Error::param("warp", format!("the warp's centre {centre} is not finite")));
        }
        Ok(Function { centre: centre.clamp(Vec3::ZERO, Vec3::ONE), end_slope })
    }

    pub fn is_none(&self) -> bool {
        self.end_slope >= 1.0
    }

    /// The largest slope (at the centre): how many times finer than the grid's voxel the finest
    /// texels are.
    pub fn peak_slope(&self) -> f32 {
        1.5 - 0.5 * self.end_slope.min(1.0)
    }

    /// The texture fraction of grid fraction `x` along `axis`.
    pub fn forward(&self, x: f64, axis: usize) -> f64 {
        let (c, a) = (self.centre[axis] as f64, self.end_slope as f64);
        if x <= 0.0 {
            a * x
        } else if x >= 1.0 {
            1.0 + a * (x - 1.0)
        } else if x < c {
            c * h(x / c, a)
        } else {
            1.0 - (1.0 - c) * h((1.0 - x) / (1.0 - c), a)
        }
    }

    /// The grid fraction of texture fraction `w` along `axis` (the inverse of [`Self::forward`]).
    pub fn inverse(&self, w: f64, axis: usize) -> f64 {
        let (c, a) = (self.centre[axis] as f64, self.end_slope as f64);
        if w <= 0.0 {
            w / a
        } else if w >= 1.0 {
            1.0 + (w - 1.0) / a
        } else if w < c {
            c * h_inverse(w / c, a)
        } else {
            1.0 - (1.0 - c) * h_inverse((1.0 - w) / (1.0 - c), a)
        }
    }

    /// dw/dx along `axis` at grid fraction `x`: the texels per unwarped texel there.
    pub fn slope(&self, x: f64, axis: usize) -> f64 {
        let (c, a) = (self.centre[axis] as f64, self.end_slope as f64);
        if x <= 0.0 || x >= 1.0 {
            a
        } else if x < c {
            h_slope(x / c, a)
        } else {
            h_slope((1.0 - x) / (1.0 - c), a)
        }
    }

    /// `vec4 warp` of the shaders: xyz the centre, w the end slope.
    pub fn gpu(&self) -> Vec4 {
        self.centre.extend(self.end_slope)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thesis' cubic, as printed (§4.6.1).
    fn thesis(x: f64, a: f64) -> f64 {
        a * x + (3.0 - 3.0 * a) * x * x + (2.0 * a - 2.0) * x * x * x
    }

    #[test]
    fn centred_warp_is_the_thesis_function() {
        let w = Function::new(Vec3::splat(0.5), 0.25).unwrap();
        for i in 0..=100 {
            let x = i as f64 / 100.0;
            assert!((w.forward(x, 0) - thesis(x, 0.25)).abs() < 1e-12, "x {x}");
        }
        assert!((w.slope(0.0, 1) - 0.25).abs() < 1e-12 && (w.slope(0.5, 1) - 1.375).abs() < 1e-12);
    }

    #[test]
    fn round_trip_is_exact_and_monotone() {
        for (c, a) in [(0.5, 0.25), (0.1, 0.25), (0.93, 0.05), (0.0, 0.5), (1.0, 0.25), (0.3, 1.0)] {
            let w = Function::new(Vec3::splat(c), a).unwrap();
            let mut last = f64::NEG_INFINITY;
            for i in -20..=1020 {
                let x = i as f64 / 1000.0;
                let y = w.forward(x, 2);
                assert!(y > last, "not increasing at {x} (c {c}, a {a})");
                last = y;
                assert!((w.inverse(y, 2) - x).abs() < 1e-12, "x {x} -> {y} -> {} (c {c}, a {a})", w.inverse(y, 2));
            }
            assert!(w.forward(0.0, 0).abs() < 1e-15 && (w.forward(1.0, 0) - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn no_warp_is_the_identity() {
        for i in 0..=10 {
            let x = i as f64 / 10.0;
            assert!((Function::NONE.forward(x, 0) - x).abs() < 1e-15);
        }
        assert!(Warp::function(Vec3::ZERO, 0.0).is_err() && Warp::function(Vec3::ZERO, 1.5).is_err());
        assert!(Warp::NONE.is_none() && Warp::NONE.proj() == Mat4::IDENTITY);
    }
}
