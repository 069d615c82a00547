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

/// The mode a key selects: its digit (top row or keypad) through the mode table's keys.
pub fn mode_for_key(key: winit::keyboard::KeyCode) -> Option<crate::render::Mode> {
    use winit::keyboard::KeyCode;
    let digit = match key {
        KeyCode::Digit1 | KeyCode::Numpad1 => 1,
        KeyCode::Digit2 | KeyCode::Numpad2 => 2,
        KeyCode::Digit3 | KeyCode::Numpad3 => 3,
        KeyCode::Digit4 | KeyCode::Numpad4 => 4,
        KeyCode::Digit5 | KeyCode::Numpad5 => 5,
        KeyCode::Digit6 | KeyCode::Numpad6 => 6,
        KeyCode::Digit7 | KeyCode::Numpad7 => 7,
        KeyCode::Digit8 | KeyCode::Numpad8 => 8,
        KeyCode::Digit9 | KeyCode::Numpad9 => 9,
        _ => return None,
    };
    crate::render::Mode::from_key(digit)
}
