//! Turning a measured map from the instrument's frame into the machine's: a mirror (x → −x or
//! y → −y) applied first, then a rotation by a multiple of 90° counter-clockwise seen from the
//! tool (+Z). Interferometers and profilometers differ from the lathe in exactly these ways (a
//! Fizeau cavity images the part mirrored; the part sits clocked on the stage), which issue 15
//! asks to correct by options rather than by editing the data.
//!
//! Every such orientation is a signed permutation of (x, y) (the eight symmetries of the
//! square), kept as its integer matrix: heights stay, points move, and a regular grid stays a
//! regular grid (its axes swap under a quarter turn), so no value is interpolated.

use super::MeasuredError;
use super::map::{HeightGrid, PointCloud};

/// Which axis a mirror flips.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mirror {
    /// No mirror.
    #[default]
    None,
    /// x → −x (left and right swap).
    X,
    /// y → −y (top and bottom swap).
    Y,
}

impl std::str::FromStr for Mirror {
    type Err = MeasuredError;

    /// `none`, `x` or `y`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "none" | "" => Ok(Mirror::None),
            "x" => Ok(Mirror::X),
            "y" => Ok(Mirror::Y),
            _ => Err(MeasuredError::Option {
                option: "mirror".into(),
                value: s.to_string(),
                allowed: "must be none, x or y".into(),
            }),
        }
    }
}

/// A mirror then a rotation by a multiple of 90° (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Orientation {
    /// `(x, y) → (m[0][0]·x + m[0][1]·y, m[1][0]·x + m[1][1]·y)`.
    m: [[i8; 2]; 2],
}

impl Default for Orientation {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Orientation {
    /// The frame as read.
    pub const IDENTITY: Orientation = Orientation {
        m: [[1, 0], [0, 1]],
    };

    /// `mirror` first, then a rotation by `rotate_deg` counter-clockwise seen from +Z; the angle
    /// is a multiple of 90 (negative turns clockwise).
    pub fn new(rotate_deg: i64, mirror: Mirror) -> Result<Self, MeasuredError> {
        if rotate_deg % 90 != 0 {
            return Err(MeasuredError::Option {
                option: "rotate_deg".into(),
                value: rotate_deg.to_string(),
                allowed: "must be a multiple of 90".into(),
            });
        }
        let quarter = Self::quarter_turns(rotate_deg.rem_euclid(360) / 90);
        let flip = match mirror {
            Mirror::None => Self::IDENTITY,
            Mirror::X => Orientation {
                m: [[-1, 0], [0, 1]],
            },
            Mirror::Y => Orientation {
                m: [[1, 0], [0, -1]],
            },
        };
        Ok(quarter.after(flip))
    }

    /// `k` quarter turns counter-clockwise.
    fn quarter_turns(k: i64) -> Self {
        let (c, s) = match k.rem_euclid(4) {
            0 => (1, 0),
            1 => (0, 1),
            2 => (-1, 0),
            _ => (0, -1),
        };
        Orientation {
            m: [[c, -s], [s, c]],
        }
    }

    /// `self` applied after `first`.
    pub fn after(self, first: Orientation) -> Orientation {
        let (a, b) = (self.m, first.m);
        let mut m = [[0i8; 2]; 2];
        for (r, row) in m.iter_mut().enumerate() {
            for (c, v) in row.iter_mut().enumerate() {
                *v = a[r][0] * b[0][c] + a[r][1] * b[1][c];
            }
        }
        Orientation { m }
    }

    /// The orientation that undoes this one (the transpose: the matrix is orthogonal).
    pub fn inverse(self) -> Orientation {
        let m = self.m;
        Orientation {
            m: [[m[0][0], m[1][0]], [m[0][1], m[1][1]]],
        }
    }

    /// Whether it includes a mirror (determinant −1).
    pub fn is_mirrored(self) -> bool {
        self.m[0][0] * self.m[1][1] - self.m[0][1] * self.m[1][0] < 0
    }

    /// The rotation, degrees in {0, 90, 180, 270}, that follows a mirror in x when
    /// [`Self::is_mirrored`], or stands alone.
    pub fn rotate_deg(self) -> u16 {
        let r = if self.is_mirrored() {
            self.after(Orientation {
                m: [[-1, 0], [0, 1]],
            })
        } else {
            self
        };
        match (r.m[0][0], r.m[1][0]) {
            (1, _) => 0,
            (0, 1) => 90,
            (-1, _) => 180,
            _ => 270,
        }
    }

    /// Where the point `(x, y)` lands.
    pub fn apply(self, x: f64, y: f64) -> (f64, f64) {
        let m = self.m.map(|r| r.map(f64::from));
        (m[0][0] * x + m[0][1] * y, m[1][0] * x + m[1][1] * y)
    }

    /// A point cloud with every point moved.
    pub fn apply_to_cloud(self, cloud: &PointCloud) -> PointCloud {
        PointCloud {
            points: cloud
                .points
                .iter()
                .map(|&[x, y, z]| {
                    let (u, v) = self.apply(x, y);
                    [u, v, z]
                })
                .collect(),
        }
    }

    /// A grid with every node moved: the result is again a regular grid (axes swapped under a
    /// quarter turn), each of its nodes the image of exactly one input node.
    pub fn apply_to_grid(self, g: &HeightGrid) -> HeightGrid {
        if g.nx == 0 || g.ny == 0 || g.z_mm.len() < g.nx * g.ny || g.valid.len() < g.nx * g.ny {
            return g.clone();
        }
        let swap = self.m[0][0] == 0;
        let (nx, ny, dx, dy) = if swap {
            (g.ny, g.nx, g.dy_mm, g.dx_mm)
        } else {
            (g.nx, g.ny, g.dx_mm, g.dy_mm)
        };
        let corners = [(0, 0), (g.nx - 1, 0), (0, g.ny - 1), (g.nx - 1, g.ny - 1)]
            .map(|(i, j)| g.node(i, j))
            .map(|[x, y]| self.apply(x, y));
        let x0 = corners.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
        let y0 = corners.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
        let back = self.inverse();
        let mut out = HeightGrid {
            x0_mm: x0,
            y0_mm: y0,
            dx_mm: dx,
            dy_mm: dy,
            nx,
            ny,
            z_mm: vec![0.0; nx * ny],
            valid: vec![false; nx * ny],
        };
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = back.apply(x0 + i as f64 * dx, y0 + j as f64 * dy);
                let si = (((x - g.x0_mm) / g.dx_mm).round() as usize).min(g.nx - 1);
                let sj = (((y - g.y0_mm) / g.dy_mm).round() as usize).min(g.ny - 1);
                let (k, sk) = (j * nx + i, sj * g.nx + si);
                out.z_mm[k] = g.z_mm[sk];
                out.valid[k] = g.valid[sk];
            }
        }
        out
    }
}

impl std::fmt::Display for Orientation {
    /// `as read`, `rotate 90°`, `mirror x, rotate 180°`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.is_mirrored(), self.rotate_deg()) {
            (false, 0) => write!(f, "as read"),
            (false, r) => write!(f, "rotate {r}°"),
            (true, 0) => write!(f, "mirror x"),
            (true, r) => write!(f, "mirror x, rotate {r}°"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn o(deg: i64, m: Mirror) -> Orientation {
        Orientation::new(deg, m).unwrap()
    }

    #[test]
    fn a_point_right_of_centre_lands_where_each_option_says() {
        // The point (3, 1): right of the centre, a little up.
        let cases = [
            (0, Mirror::None, (3.0, 1.0)),
            (90, Mirror::None, (-1.0, 3.0)),
            (180, Mirror::None, (-3.0, -1.0)),
            (270, Mirror::None, (1.0, -3.0)),
            (-90, Mirror::None, (1.0, -3.0)),
            (0, Mirror::X, (-3.0, 1.0)),
            (0, Mirror::Y, (3.0, -1.0)),
            // Mirror first: (3, 1) → (−3, 1), then a quarter turn → (−1, −3).
            (90, Mirror::X, (-1.0, -3.0)),
        ];
        for (deg, m, want) in cases {
            assert_eq!(o(deg, m).apply(3.0, 1.0), want, "{deg} {m:?}");
        }
    }

    #[test]
    fn composition_inverse_and_names() {
        assert_eq!(
            o(90, Mirror::None).after(o(270, Mirror::None)),
            Orientation::IDENTITY
        );
        assert_eq!(o(180, Mirror::X), o(0, Mirror::Y));
        for deg in [0, 90, 180, 270] {
            for m in [Mirror::None, Mirror::X, Mirror::Y] {
                let t = o(deg, m);
                assert_eq!(t.inverse().after(t), Orientation::IDENTITY);
                let named = Orientation::new(
                    i64::from(t.rotate_deg()),
                    if t.is_mirrored() {
                        Mirror::X
                    } else {
                        Mirror::None
                    },
                );
                assert_eq!(named.unwrap(), t, "{t}");
            }
        }
        assert_eq!(o(90, Mirror::X).to_string(), "mirror x, rotate 90°");
        assert_eq!(o(0, Mirror::None).to_string(), "as read");
        assert_eq!("Y".parse::<Mirror>().unwrap(), Mirror::Y);
        assert!("z".parse::<Mirror>().is_err());
    }
}
