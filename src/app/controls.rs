//! Mouse and keyboard control of the camera. The orbit camera: drag to orbit, wheel to zoom,
//! right or middle drag to pan. The fly camera (F toggles): W/A/S/D to move, Q/E or Ctrl/Space
//! down and up, Shift faster, drag to look around. R resets to the framing of the model.

use std::time::Instant;

use glam::{Vec3, Vec4Swizzles};
use winit::event::{ElementState, MouseButton, MouseScrollDelta};
use winit::keyboard::KeyCode;

use crate::scene::OrbitCamera;

/// Degrees of orbit per pixel of drag.
const ORBIT_SPEED: f32 = 0.3;
/// Degrees the fly camera turns per pixel of drag.
const LOOK_SPEED: f32 = 0.15;
/// The fly camera's speed in bounding radii per second, and how much faster with Shift.
const FLY_SPEED: f32 = 0.5;
const FLY_FAST: f32 = 4.0;
/// The longest step one frame takes (a frame after a pause does not jump).
const MAX_STEP_SECONDS: f32 = 0.1;

/// The fly camera's keys and the direction each moves in: (forward, right, up).
const FLY_KEYS: [(KeyCode, [f32; 3]); 10] = [
    (KeyCode::KeyW, [1.0, 0.0, 0.0]),
    (KeyCode::KeyS, [-1.0, 0.0, 0.0]),
    (KeyCode::KeyD, [0.0, 1.0, 0.0]),
    (KeyCode::KeyA, [0.0, -1.0, 0.0]),
    (KeyCode::KeyE, [0.0, 0.0, 1.0]),
    (KeyCode::Space, [0.0, 0.0, 1.0]),
    (KeyCode::KeyQ, [0.0, 0.0, -1.0]),
    (KeyCode::ControlLeft, [0.0, 0.0, -1.0]),
    (KeyCode::ControlRight, [0.0, 0.0, -1.0]),
    (KeyCode::ShiftLeft, [0.0; 3]),
];

#[derive(Default)]
pub struct CameraControls {
    orbiting: bool,
    panning: bool,
    last: Option<(f64, f64)>,
    /// The fly camera is on: drags look, keys move.
    pub fly: bool,
    /// The fly keys held down, and when the camera last stepped.
    held: Vec<KeyCode>,
    last_step: Option<Instant>,
}

impl CameraControls {
    /// Controls with the fly camera on or off (on for a view started from `--eye`).
    pub fn flying_from_start(fly: bool) -> Self {
        Self { fly, ..Self::default() }
    }

    /// Whether a drag is moving the camera.
    pub fn dragging(&self) -> bool {
        self.orbiting || self.panning
    }

    /// Whether a fly key is held, so the camera moves every frame.
    pub fn flying(&self) -> bool {
        self.held.iter().any(|k| *k != KeyCode::ShiftLeft && *k != KeyCode::ShiftRight)
    }

    /// Takes a fly key's press or release; returns whether the key is one (and the fly camera on).
    pub fn fly_key(&mut self, key: KeyCode, state: ElementState) -> bool {
        let key = if key == KeyCode::ShiftRight { KeyCode::ShiftLeft } else { key };
        if !self.fly || !FLY_KEYS.iter().any(|(k, _)| *k == key) {
            return false;
        }
        self.held.retain(|k| *k != key);
        if state == ElementState::Pressed {
            self.held.push(key);
            self.last_step.get_or_insert_with(Instant::now);
        }
        true
    }

    /// Turns the fly camera on or off; off lets go of every key.
    pub fn set_fly(&mut self, on: bool) {
        self.fly = on;
        self.held.clear();
        self.last_step = None;
    }

    /// Moves the fly camera by the keys held since the last step, at a speed in `radius` (the
    /// scene's bounding radius) per second; returns whether it moved.
    pub fn step(&mut self, camera: &mut OrbitCamera, radius: f32, now: Instant) -> bool {
        let Some(last) = self.last_step.replace(now) else { return false };
        if !self.flying() {
            self.last_step = None;
            return false;
        }
        let seconds = now.duration_since(last).as_secs_f32().min(MAX_STEP_SECONDS);
        let direction: Vec3 = FLY_KEYS.iter().filter(|(k, _)| self.held.contains(k)).map(|(_, d)| Vec3::from(*d)).sum();
        let fast = if self.held.contains(&KeyCode::ShiftLeft) { FLY_FAST } else { 1.0 };
        let forward = camera.forward();
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
        let by = (forward * direction.x + right * direction.y + Vec3::Y * direction.z) * radius * FLY_SPEED * fast;
        camera.translate(by * seconds);
        seconds > 0.0
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
        if self.orbiting && self.fly {
            // Drag right to look right, down to look down.
            camera.turn(-dx * LOOK_SPEED, dy * LOOK_SPEED);
            return true;
        }
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
