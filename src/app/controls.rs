//! Mouse and keyboard control of the orbit camera: drag to orbit, wheel to zoom, right or middle
//! drag to pan, R to reset to the framing of the model.

use glam::{Vec3, Vec4Swizzles};
use winit::event::{ElementState, MouseButton, MouseScrollDelta};

use crate::scene::OrbitCamera;

/// Degrees of orbit per pixel of drag.
const ORBIT_SPEED: f32 = 0.3;

#[derive(Default)]
pub struct CameraControls {
    orbiting: bool,
    panning: bool,
    last: Option<(f64, f64)>,
}

impl CameraControls {
    /// Whether a drag is moving the camera.
    pub fn dragging(&self) -> bool {
        self.orbiting || self.panning
    }

    pub fn button(&mut self, button: MouseButton, state: ElementState, over_view: bool) {
        let pressed = state == ElementState::Pressed && over_view;
        match button {
            MouseButton::Left => self.orbiting = pressed,
            MouseButton::Right | MouseButton::Middle => self.panning = pressed,
            _ => {}
        }
    }

    /// Applies a cursor move; returns whether the camera changed.
    pub fn moved(&mut self, camera: &mut OrbitCamera, x: f64, y: f64, view_height: u32) -> bool {
        let previous = self.last.replace((x, y));
        let Some((px, py)) = previous else { return false };
        let (dx, dy) = ((x - px) as f32, (y - py) as f32);
        if self.orbiting {
            camera.yaw_deg -= dx * ORBIT_SPEED;
            camera.pitch_deg = (camera.pitch_deg + dy * ORBIT_SPEED).clamp(-89.0, 89.0);
            return true;
        }
        if self.panning {
            // Move the target in the view plane so the point under the cursor follows it.
            let scale = 2.0 * camera.distance * (0.5 * camera.fov_y_deg.to_radians()).tan() / view_height.max(1) as f32;
            let view_to_world = camera.world_to_view().inverse();
            let right = (view_to_world * Vec3::X.extend(0.0)).xyz();
            let up = (view_to_world * Vec3::Y.extend(0.0)).xyz();
            camera.target += (-dx * right + dy * up) * scale;
            return true;
        }
        false
    }

    /// Zooms by a wheel step; returns whether the camera changed.
    pub fn wheel(&mut self, camera: &mut OrbitCamera, delta: MouseScrollDelta) -> bool {
        let steps = match delta {
            MouseScrollDelta::LineDelta(_, y) => y,
            MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
        };
        if steps == 0.0 || !steps.is_finite() {
            return false;
        }
        let distance = camera.distance * 0.9f32.powf(steps);
        camera.near *= distance / camera.distance;
        camera.distance = distance;
        true
    }
}
