//! Orbit camera for the 3-D view, pure glam math: the eye sits on a sphere around a target
//! point (yaw about the world Z axis, pitch above the XY plane, distance), looking at the target
//! with Z up, through a right-handed perspective projection with WebGPU's 0..1 depth range.
//! The scene is a box of half-size [`OrbitCamera::extent`] about the origin; the default view
//! fits the box's corners to the canvas, and near/far planes follow its bounding sphere.

use glam::camera::rh::{proj::directx, view};
use glam::{Mat4, Vec3};

/// Vertical field of view (radians).
const FOV_Y: f32 = 30.0 * std::f32::consts::PI / 180.0;
/// Default elevation above the part (radians).
const DEFAULT_PITCH: f32 = 35.0 * std::f32::consts::PI / 180.0;
/// Default azimuth: the eye on −Y, looking towards +Y, so +X points right on screen.
const DEFAULT_YAW: f32 = -std::f32::consts::FRAC_PI_2;
/// Pitch limit, short of the poles where the Z-up view matrix degenerates (radians).
const MAX_PITCH: f32 = 89.0 * std::f32::consts::PI / 180.0;
/// Orbit speed (radians per CSS pixel of drag).
const ORBIT_PER_PIXEL: f32 = 0.01;
/// Zoom range relative to the distance at which the scene's bounding sphere fits.
const ZOOM_RANGE: (f32, f32) = (0.02, 20.0);
/// Fraction of the viewport the fitted scene spans at most, in each direction.
pub const FILL: f32 = 0.92;

/// An orbit camera about a target point, Z up.
#[derive(Clone, Debug)]
pub struct OrbitCamera {
    /// The point looked at (world units).
    pub target: Vec3,
    /// Azimuth of the eye about +Z, from +X (radians).
    pub yaw: f32,
    /// Elevation of the eye above the target's XY plane (radians).
    pub pitch: f32,
    /// Eye-to-target distance (world units).
    pub distance: f32,
    /// Half-size of the scene's bounding box, centred on the origin (world units).
    pub extent: Vec3,
    /// Viewport width / height.
    pub aspect: f32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        let mut camera = Self {
            target: Vec3::ZERO,
            yaw: DEFAULT_YAW,
            pitch: DEFAULT_PITCH,
            distance: 1.0,
            extent: Vec3::ONE,
            aspect: 1.0,
        };
        camera.reset();
        camera
    }
}

impl OrbitCamera {
    /// Radius of the scene's bounding sphere.
    pub fn radius(&self) -> f32 {
        self.extent.length().max(f32::MIN_POSITIVE)
    }

    /// The smallest distance from the origin, in the current direction, at which every corner
    /// of the scene box lies within [`FILL`] of the viewport.
    pub fn fit_distance(&self) -> f32 {
        let tan_v = FILL * (FOV_Y / 2.0).tan();
        let tan_h = tan_v * self.aspect;
        let back = self.backward();
        let (right, up) = self.right_up();
        let mut distance = 0.1 * self.radius();
        for corner in 0..8 {
            let sign = |bit: u32| if corner & bit == 0 { -1.0 } else { 1.0 };
            let p = self.extent * Vec3::new(sign(1), sign(2), sign(4));
            // The corner's depth in front of the eye is distance − p·back.
            let towards_eye = p.dot(back);
            distance = distance
                .max(towards_eye + p.dot(right).abs() / tan_h)
                .max(towards_eye + p.dot(up).abs() / tan_v);
        }
        distance
    }

    /// Back to the default view: target at the origin, seen from −Y at 35° elevation, fitted.
    pub fn reset(&mut self) {
        self.target = Vec3::ZERO;
        self.yaw = DEFAULT_YAW;
        self.pitch = DEFAULT_PITCH;
        self.distance = self.fit_distance();
    }

    /// Unit vector from the target towards the eye.
    fn backward(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(cp * cy, cp * sy, sp)
    }

    /// The eye position.
    pub fn eye(&self) -> Vec3 {
        self.target + self.distance * self.backward()
    }

    /// Screen-right and screen-up unit vectors in world space.
    pub fn right_up(&self) -> (Vec3, Vec3) {
        let forward = -self.backward();
        let right = forward.cross(Vec3::Z).normalize();
        (right, right.cross(forward))
    }

    /// Rotates about the target by a drag of `dx`, `dy` CSS pixels: the part follows the pointer.
    pub fn orbit(&mut self, dx: f32, dy: f32) {
        if !(dx.is_finite() && dy.is_finite()) {
            return;
        }
        self.yaw = (self.yaw - dx * ORBIT_PER_PIXEL).rem_euclid(std::f32::consts::TAU);
        self.pitch = (self.pitch + dy * ORBIT_PER_PIXEL).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the target in the view plane by a drag of `dx`, `dy` CSS pixels on a viewport
    /// `css_height` pixels high, so that the point under the pointer follows it.
    pub fn pan(&mut self, dx: f32, dy: f32, css_height: f32) {
        if !(dx.is_finite() && dy.is_finite()) {
            return;
        }
        let per_pixel = 2.0 * self.distance * (FOV_Y / 2.0).tan() / css_height.max(1.0);
        let (right, up) = self.right_up();
        self.target += per_pixel * (up * dy - right * dx);
    }

    /// Divides the distance by `factor` (> 1 zooms in), within 2 %..2000 % of the distance at
    /// which the scene's bounding sphere fits the height of the view.
    pub fn zoom(&mut self, factor: f32) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        let fit = self.radius() / (FOV_Y / 2.0).sin();
        self.distance = (self.distance / factor).clamp(ZOOM_RANGE.0 * fit, ZOOM_RANGE.1 * fit);
    }

    /// The view-projection matrix; near and far planes enclose the scene sphere.
    pub fn view_proj(&self) -> Mat4 {
        let eye = self.eye();
        let look = view::look_at_mat4(eye, self.target, Vec3::Z);
        let to_centre = eye.length();
        let radius = self.radius();
        let near = (to_centre - 1.5 * radius).max(1e-3 * radius);
        let far = (to_centre + 1.5 * radius).max(2.0 * near);
        directx::perspective(FOV_Y, self.aspect, near, far) * look
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4Swizzles;

    fn ndc(camera: &OrbitCamera, p: Vec3) -> Vec3 {
        let c = camera.view_proj() * p.extend(1.0);
        c.xyz() / c.w
    }

    #[test]
    fn default_view_fits_the_scene_and_looks_from_minus_y() {
        let mut camera = OrbitCamera {
            extent: Vec3::new(5.0, 5.0, 0.75),
            aspect: 4.0 / 3.0,
            ..OrbitCamera::default()
        };
        camera.reset();
        let eye = camera.eye();
        assert!(eye.y < 0.0 && eye.z > 0.0 && eye.x.abs() < 1e-4);
        let (right, _) = camera.right_up();
        assert!((right - Vec3::X).length() < 1e-5);
        let mut widest = 0.0_f32;
        for corner in 0..8 {
            let sign = |bit: u32| if corner & bit == 0 { -1.0 } else { 1.0 };
            let q = ndc(
                &camera,
                camera.extent * Vec3::new(sign(1), sign(2), sign(4)),
            );
            assert!(q.x.abs() <= FILL + 1e-4 && q.y.abs() <= FILL + 1e-4, "{q}");
            assert!((0.0..1.0).contains(&q.z), "{q}");
            widest = widest.max(q.x.abs()).max(q.y.abs());
        }
        assert!(widest > FILL - 1e-3, "fitted loosely: {widest}");
        // +X maps to the right of the screen.
        assert!(ndc(&camera, Vec3::X).x > 0.0);
    }

    #[test]
    fn pan_moves_the_target_with_the_pointer() {
        let mut camera = OrbitCamera {
            extent: Vec3::new(5.0, 5.0, 0.75),
            ..OrbitCamera::default()
        };
        camera.reset();
        let before = ndc(&camera, Vec3::ZERO);
        camera.pan(10.0, 0.0, 480.0);
        let after = ndc(&camera, Vec3::ZERO);
        assert!(after.x > before.x, "{before} -> {after}");
        camera.pan(0.0, 10.0, 480.0);
        assert!(ndc(&camera, Vec3::ZERO).y < after.y);
    }

    #[test]
    fn zoom_and_orbit_are_clamped() {
        let mut camera = OrbitCamera::default();
        let fit = camera.radius() / (FOV_Y / 2.0).sin();
        let start = camera.distance;
        camera.zoom(2.0);
        assert!((camera.distance - start / 2.0).abs() < 1e-5);
        camera.zoom(1e9);
        assert!((camera.distance - ZOOM_RANGE.0 * fit).abs() < 1e-5);
        camera.zoom(0.0);
        camera.zoom(f32::NAN);
        assert!(camera.distance.is_finite());
        camera.orbit(0.0, 1e6);
        assert!((camera.pitch - MAX_PITCH).abs() < 1e-6);
        assert!(camera.view_proj().is_finite());
    }
}
