//! What the page draws, kept apart from what the machine gets: the path decimated to a fixed
//! point budget, and the surface sampled on a polar mesh with analytic normals. Both are flat
//! `f32` arrays ready for GPU buffers. Decimation is for display only; the NC and CSV always
//! carry every point.

use crate::path::PathPoint;
use crate::surface::{Surface, UndefinedError};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// The decimated path as line segments (x, y, z pairs, z the sag at the contact point so the
/// line lies on the drawn surface): only every `every`-th revolution, so that at most about
/// [`DISPLAY_REVOLUTIONS`] are drawn (hundreds of passes 10 µm apart are denser than the
/// pixels), and along those every `stride`-th point, so that at most about `budget` points are
/// kept.
///
/// A slice of the path (the page's workers) is drawn by a copy [started](DisplayPath::starting_at)
/// at its first index and [merged](DisplayPath::merge) in order: the same segments as one walk.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DisplayPath {
    every: u64,
    stride: u64,
    theta0: Option<f64>,
    last: Option<[f32; 3]>,
    /// Segments: two x y z points each, mm (not serialised: they travel as an array).
    #[serde(skip)]
    pub segments: Vec<f32>,
    seen: u64,
    /// How the copy began: its first kept point, joined to the point kept before it, or a
    /// revolution left out (the line broken).
    head: Head,
}

/// The first event of a display copy.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
enum Head {
    /// No point yet.
    #[default]
    Empty,
    /// A point kept first.
    Joins([f32; 3]),
    /// A point left out first.
    Broken,
}

/// The most revolutions drawn.
pub const DISPLAY_REVOLUTIONS: f64 = 80.0;

impl DisplayPath {
    /// A display copy of a path of `total` points over `revolutions` turns, keeping at most about
    /// `budget` points.
    pub fn new(total: u64, revolutions: f64, budget: u64) -> Self {
        let every = (revolutions / DISPLAY_REVOLUTIONS).ceil().max(1.0) as u64;
        let kept = total / every + 1;
        let stride = kept.div_ceil(budget.max(1)).max(1);
        Self {
            every,
            stride,
            ..Default::default()
        }
    }

    /// The copy of the slice of the path from its `first` point on, `theta0` the angle of the
    /// path's first point.
    pub fn starting_at(mut self, first: u64, theta0: f64) -> Self {
        (self.seen, self.theta0) = (first, Some(theta0));
        self
    }

    /// This copy followed by `later`'s, the copy of the slice right after it.
    pub fn merge(mut self, mut later: DisplayPath) -> Self {
        if let (Some(prev), Head::Joins(xyz)) = (self.last, later.head) {
            self.segments.extend_from_slice(&prev);
            self.segments.extend_from_slice(&xyz);
        }
        self.segments.append(&mut later.segments);
        if self.head == Head::Empty {
            self.head = later.head;
        }
        if later.head != Head::Empty {
            self.last = later.last;
        }
        self.seen = later.seen;
        self.theta0 = self.theta0.or(later.theta0);
        self
    }

    /// Only every this many revolutions is drawn.
    pub fn revolution_step(&self) -> u64 {
        self.every
    }

    /// Offers one point.
    pub fn push(&mut self, p: &PathPoint) {
        let theta0 = *self.theta0.get_or_insert(p.theta);
        // The epsilon keeps a point at a whole turn in its own revolution despite rounding.
        let rev = ((p.theta - theta0).abs() / TAU + 1e-9) as u64;
        let on_stride = self.seen.is_multiple_of(self.stride) || p.rho == 0.0;
        self.seen += 1;
        if !rev.is_multiple_of(self.every) && p.rho != 0.0 {
            self.last = None;
            if self.head == Head::Empty {
                self.head = Head::Broken;
            }
            return;
        }
        if !on_stride {
            return;
        }
        let (s, c) = p.theta.sin_cos();
        let xyz = [(p.rho * c) as f32, (p.rho * s) as f32, p.contact[2] as f32];
        if let Some(prev) = self.last {
            self.segments.extend_from_slice(&prev);
            self.segments.extend_from_slice(&xyz);
        }
        if self.head == Head::Empty {
            self.head = Head::Joins(xyz);
        }
        self.last = Some(xyz);
    }

    /// Segments kept.
    pub fn len(&self) -> usize {
        self.segments.len() / 6
    }

    /// No segment kept.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }
}

/// The surface on a polar mesh: `rings` circles from the centre to the part edge, `spokes`
/// points on each, plus the centre.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMesh {
    /// x, y, z per vertex, mm.
    pub positions: Vec<f32>,
    /// Unit normals per vertex.
    pub normals: Vec<f32>,
    /// Triangles, three vertex indices each.
    pub indices: Vec<u32>,
    /// Lowest sag, mm.
    pub z_min: f64,
    /// Highest sag, mm.
    pub z_max: f64,
}

impl SurfaceMesh {
    /// Samples `surface` out to `radius` mm at about eight vertices per feature length
    /// ([`Surface::feature_length_mm`]), between 64 × 128 and 400 × 1024 vertices.
    pub fn for_surface(surface: &dyn Surface, radius: f64) -> Result<Self, UndefinedError> {
        let spacing = surface.feature_length_mm() / 8.0;
        let rings = (radius / spacing).ceil().clamp(64.0, 400.0) as u32;
        let spokes = (TAU * radius / spacing).ceil().clamp(128.0, 1024.0) as u32;
        Self::new(surface, radius, rings, spokes)
    }

    /// Samples `surface` out to `radius` mm.
    pub fn new(
        surface: &dyn Surface,
        radius: f64,
        rings: u32,
        spokes: u32,
    ) -> Result<Self, UndefinedError> {
        let (rings, spokes) = (rings.max(1), spokes.max(3));
        let vertices = 1 + (rings * spokes) as usize;
        let mut mesh = Self {
            positions: Vec::with_capacity(3 * vertices),
            normals: Vec::with_capacity(3 * vertices),
            indices: Vec::with_capacity(6 * (rings * spokes) as usize),
            z_min: f64::INFINITY,
            z_max: f64::NEG_INFINITY,
        };
        mesh.vertex(surface, 0.0, 0.0)?;
        for i in 1..=rings {
            let rho = radius * i as f64 / rings as f64;
            for j in 0..spokes {
                let (s, c) = (TAU * j as f64 / spokes as f64).sin_cos();
                mesh.vertex(surface, rho * c, rho * s)?;
            }
        }
        let at = |ring: u32, spoke: u32| 1 + (ring - 1) * spokes + spoke % spokes;
        for j in 0..spokes {
            mesh.indices.extend_from_slice(&[0, at(1, j), at(1, j + 1)]);
        }
        for i in 1..rings {
            for j in 0..spokes {
                let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
                mesh.indices.extend_from_slice(&[a, c, d, a, d, b]);
            }
        }
        Ok(mesh)
    }

    fn vertex(&mut self, surface: &dyn Surface, x: f64, y: f64) -> Result<(), UndefinedError> {
        let l = surface.local(x, y)?;
        self.positions
            .extend_from_slice(&[x as f32, y as f32, l.z as f32]);
        self.normals.extend(l.normal().map(|v| v as f32));
        self.z_min = self.z_min.min(l.z);
        self.z_max = self.z_max.max(l.z);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Asphere, AsphereSpec};

    #[test]
    fn mesh_covers_the_disc_with_consistent_indices() {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(10.0),
            ..Default::default()
        })
        .unwrap();
        let m = SurfaceMesh::new(&s, 5.0, 8, 16).unwrap();
        assert_eq!(m.positions.len(), 3 * (1 + 8 * 16));
        assert_eq!(m.indices.len(), 3 * 16 + 6 * 7 * 16);
        assert!(
            m.indices
                .iter()
                .all(|&i| (i as usize) < m.positions.len() / 3)
        );
        assert_eq!(m.z_min, 0.0);
        assert!((m.z_max - (10.0 - 75f64.sqrt())).abs() < 1e-12);
    }

    #[test]
    fn decimation_keeps_every_kth_revolution_within_budget() {
        // 400 revolutions of 100 points: every 5th revolution, every point of those.
        let mut d = DisplayPath::new(40_001, 400.0, 1_000_000);
        assert_eq!(d.revolution_step(), 5);
        for i in 0..=40_000u64 {
            let theta = TAU * i as f64 / 100.0;
            let rho = 4.0 * (1.0 - i as f64 / 40_000.0);
            let p = PathPoint {
                index: i,
                rho,
                theta,
                z: 0.0,
                contact: [0.0; 3],
                contact_angle: 0.0,
                at_arc_end: false,
            };
            d.push(&p);
        }
        // 80 kept revolutions of 100 points give 99 segments each; the centre point (revolution
        // 400) has no kept neighbour, since revolution 399 is not kept.
        assert_eq!(d.len(), 80 * 99);
        // Every segment joins points 1/100 of a turn apart.
        for seg in d.segments.chunks(6) {
            let a = (seg[1] as f64).atan2(seg[0] as f64);
            let b = (seg[4] as f64).atan2(seg[3] as f64);
            let step = (b - a).rem_euclid(TAU);
            assert!((step - TAU / 100.0).abs() < 1e-5, "{step}");
        }
        let mut thin = DisplayPath::new(40_001, 400.0, 1_000);
        assert_eq!(thin.revolution_step(), 5);
        for i in 0..=40_000u64 {
            let p = PathPoint {
                index: i,
                rho: 1.0,
                theta: TAU * i as f64 / 100.0,
                z: 0.0,
                contact: [0.0; 3],
                contact_angle: 0.0,
                at_arc_end: false,
            };
            thin.push(&p);
        }
        assert!(thin.len() <= 1_000, "{}", thin.len());
    }
}
