//! What the page draws, kept apart from what the machine gets: the path decimated to a fixed
//! point budget, and the surface sampled on a polar mesh with analytic normals. Both are flat
//! `f32` arrays ready for GPU buffers. Decimation is for display only; the NC and CSV always
//! carry every point.

use crate::plan::PathPoint;
use crate::surface::{Surface, UndefinedError};
use std::f64::consts::TAU;

/// The decimated path: every `stride`-th point as (x, y, z) with z the sag at the contact point
/// (so the line lies on the drawn surface).
#[derive(Debug, Clone, Default)]
pub struct DisplayPath {
    stride: u64,
    /// x, y, z triples, mm.
    pub xyz: Vec<f32>,
    seen: u64,
}

impl DisplayPath {
    /// A path that keeps at most about `budget` of `total` points.
    pub fn new(total: u64, budget: u64) -> Self {
        let stride = total.div_ceil(budget.max(1)).max(1);
        Self {
            stride,
            xyz: Vec::with_capacity(3 * (total / stride + 2) as usize),
            seen: 0,
        }
    }

    /// Offers one point; keeps it if it falls on the stride.
    pub fn push(&mut self, p: &PathPoint) {
        if self.seen.is_multiple_of(self.stride) || p.rho == 0.0 {
            let (s, c) = p.theta.sin_cos();
            self.xyz.extend_from_slice(&[
                (p.rho * c) as f32,
                (p.rho * s) as f32,
                p.contact[2] as f32,
            ]);
        }
        self.seen += 1;
    }

    /// Points kept.
    pub fn len(&self) -> usize {
        self.xyz.len() / 3
    }

    /// No point kept.
    pub fn is_empty(&self) -> bool {
        self.xyz.is_empty()
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
    fn decimation_keeps_the_budget_and_the_centre() {
        let mut d = DisplayPath::new(1000, 100);
        for i in 0..1000u64 {
            let rho = if i == 999 { 0.0 } else { 1.0 };
            let p = PathPoint {
                index: i,
                rho,
                theta: 0.0,
                z: 0.0,
                contact: [0.0; 3],
                contact_angle: 0.0,
                at_arc_end: false,
            };
            d.push(&p);
        }
        assert_eq!(d.len(), 101);
    }
}
