//! The egui side panel: modes, variant and debug view, sampling parameters, lights, sky and
//! model, camera, screenshots, per-pass GPU timings and the last messages. Drawing the panel
//! changes the settings in place and returns the actions that need the application.

use std::path::PathBuf;

use super::panel_state::{Action, PanelState, PANEL_WIDTH};
use crate::render::{Mode, Settings, Variant, View};

fn slider(ui: &mut egui::Ui, value: &mut f32, range: std::ops::RangeInclusive<f32>, text: &str) {
    ui.add(egui::Slider::new(value, range).text(text));
}

/// A path typed into a text field and a "load" button: the path when the button is pressed on a
/// field that is not blank.
fn path_field(ui: &mut egui::Ui, text: &mut String, hint: &str) -> Option<PathBuf> {
    ui.horizontal(|ui| {
        ui.add(egui::TextEdit::singleline(text).hint_text(hint).desired_width(PANEL_WIDTH - 80.0));
        let pressed = ui.button("load").clicked();
        (pressed && !text.trim().is_empty()).then(|| PathBuf::from(text.trim()))
    })
    .inner
}

/// Draws the panel; returns what the application has to do.
pub fn panel(ui: &mut egui::Ui, state: &mut PanelState, settings: &mut Settings, default_radius: f32) -> Vec<Action> {
    let mut actions = Vec::new();
    egui::Panel::left("controls").exact_size(PANEL_WIDTH).resizable(false).show(ui, |ui| {
        egui::ScrollArea::vertical().show(ui, |ui| {
            status(ui, state);
            ui.separator();
            mode_section(ui, settings, &mut actions);
            ui.separator();
            super::truth_ui::section(ui, &mut state.truth, settings.mode);
            ui.separator();
            preset_section(ui, state, settings, &mut actions);
            ui.separator();
            sampling_section(ui, state, settings, default_radius);
            lighting_section(ui, settings);
            ui.separator();
            lights_section(ui, state, &mut actions);
            ui.separator();
            files_section(ui, state, &mut actions);
            ui.separator();
            camera_section(ui, state, &mut actions);
            ui.separator();
            timings_section(ui, state);
        });
    });
    actions
}

/// The adapter, the files on screen, a load in progress and the last messages.
fn status(ui: &mut egui::Ui, state: &PanelState) {
    ui.heading("ssdo");
    ui.label(format!("{}\nmodel: {}\nsky: {}", state.adapter, state.model_name, state.sky_name));
    if let Some(progress) = &state.loading {
        ui.label(progress);
    }
    for m in &state.messages {
        let color =
            if m.error { egui::Color32::from_rgb(255, 110, 110) } else { egui::Color32::from_rgb(140, 220, 140) };
        ui.colored_label(color, &m.text);
    }
}

/// The mode buttons, the variant and the debug view.
fn mode_section(ui: &mut egui::Ui, settings: &mut Settings, actions: &mut Vec<Action>) {
    ui.label("Mode (keys 1-4)");
    ui.horizontal_wrapped(|ui| {
        for mode in Mode::ALL {
            if ui.selectable_label(settings.mode == mode, format!("{} {}", mode.key(), mode.title())).clicked() {
                actions.push(Action::Mode(mode));
            }
        }
    });
    egui::ComboBox::from_label("variant").selected_text(settings.knobs.variant.name()).show_ui(ui, |ui| {
        for v in Variant::ALL {
            ui.selectable_value(&mut settings.knobs.variant, v, v.name());
        }
    });
    egui::ComboBox::from_label("view").selected_text(settings.view.title()).show_ui(ui, |ui| {
        for v in View::ALL {
            ui.selectable_value(&mut settings.view, v, v.title());
        }
    });
}

/// The quality levels, a preset file, and what the preset taken expects beside what this frame
/// measures.
fn preset_section(ui: &mut egui::Ui, state: &mut PanelState, settings: &mut Settings, actions: &mut Vec<Action>) {
    use crate::preset::Quality;
    // The level whose knobs the settings hold now, if any.
    let current = Quality::ALL.into_iter().find(|q| settings.with_knobs(q.knobs()) == *settings);
    let mut chosen = current;
    egui::ComboBox::from_label("quality")
        .selected_text(current.map_or("custom", Quality::name))
        .show_ui(ui, |ui| {
            for q in Quality::ALL {
                ui.selectable_value(&mut chosen, Some(q), q.name());
            }
        })
        .response
        .on_hover_text("tune's picks on the default scene at multiples of the Off frame's time (docs/quality.md)");
    if let Some(level) = chosen.filter(|&q| Some(q) != current) {
        *settings = settings.with_knobs(level.knobs());
        state.preset = Some(level.preset());
    }
    ui.label("Preset file (from ssdo tune)");
    if let Some(path) = path_field(ui, &mut state.preset_path, "tune/preset.json") {
        actions.push(Action::LoadPreset(path));
    }
    if let Some(preset) = &state.preset {
        let now: f64 = state.timings.iter().map(|(_, ms)| ms).sum();
        let expected = preset.measured.as_ref().map_or_else(
            || "no measured figures (the levels': docs/quality.md)".to_string(),
            |m| {
                format!("expected {:.2} ms, HDR RMSE {:.4} ({}x{}, {})", m.ms, m.hdr_rmse, m.size.0, m.size.1, m.device)
            },
        );
        ui.label(format!("{}: {expected}; now {now:.2} ms (GPU)", preset.name));
    }
}

/// The panel's name of the knob with preset key `key` (`crate::knobs::KNOBS`).
fn knob_label(key: &str) -> &'static str {
    crate::knobs::KNOBS.iter().find(|k| k.key == key).map_or("?", |k| k.label)
}

/// The variant's counts and lengths, the bias, blur, half resolution and accumulation.
fn sampling_section(ui: &mut egui::Ui, state: &mut PanelState, settings: &mut Settings, default_radius: f32) {
    ui.label("Sampling");
    for count in settings.knobs.variant.decl().counts {
        let value = settings.knobs.count_mut(count.id);
        ui.add(egui::Slider::new(value, count.range()).logarithmic(true).text(count.label));
    }
    // A length with a scene-derived default: the slider shows the default until moved.
    let length = |ui: &mut egui::Ui, value: &mut Option<f32>, default: f32, max: f32, text: &str| {
        let mut v = value.unwrap_or(default);
        let before = v;
        ui.add(egui::Slider::new(&mut v, 0.0..=max).text(text));
        if v != before {
            *value = Some(v);
        }
    };
    // The lengths in use (a preset's multiples made this scene's), within the sliders' ranges.
    let now = settings.lengths(default_radius);
    let defaults = Settings::default().lengths(default_radius);
    length(ui, &mut settings.given.radius, now.radius, (default_radius * 5.0).max(now.radius), "radius");
    if settings.knobs.variant.decl().marched_lengths {
        length(ui, &mut settings.given.reach, now.reach, (defaults.reach * 4.0).max(now.reach), "reach");
        let thickness = (defaults.thickness * 10.0).max(now.thickness);
        length(ui, &mut settings.given.thickness, now.thickness, thickness, "thickness");
    }
    slider(ui, &mut settings.given.bias, 0.0..=0.3, "bias (× radius)");
    // The switches, from their knobs: those that mean anything for this variant and mode.
    let (knobs, mode) = (settings.knobs, settings.mode);
    for knob in crate::knobs::switches().filter(|k| k.applies(&knobs, Some(mode))) {
        let mut on = knob.is_on(&settings.knobs);
        if ui.checkbox(&mut on, knob.label).on_hover_text(knob.help).changed() {
            knob.turn(&mut settings.knobs, on);
        }
    }
    // Accumulation: on with the last count it had, off as 1 frame.
    let mut on = settings.accumulates();
    ui.horizontal(|ui| {
        if ui.checkbox(&mut on, "accumulate").on_hover_text("average the frames of a still view (T)").changed() {
            settings.knobs.accumulate = if on { state.accumulate.max(2) } else { 1 };
        }
        if on {
            ui.label(format!("{} / {} frames", state.still_frames, settings.knobs.accumulate));
        }
    });
    if on {
        let count = crate::render::ACCUMULATE;
        ui.add(egui::Slider::new(&mut settings.knobs.accumulate, 2..=count.max).logarithmic(true).text("frames"));
        state.accumulate = settings.knobs.accumulate;
    }
}

/// The strengths, the bounce's senders, exposure, ambient and the sky's scale.
fn lighting_section(ui: &mut egui::Ui, settings: &mut Settings) {
    slider(ui, &mut settings.ao_strength, 0.0..=1.0, "AO strength");
    slider(ui, &mut settings.ao_power, 0.25..=4.0, "AO power");
    slider(ui, &mut settings.sky_strength, 0.0..=4.0, "sky strength");
    slider(ui, &mut settings.knobs.indirect_strength, 0.0..=8.0, "indirect strength");
    egui::ComboBox::from_label(knob_label("sender_sky"))
        .selected_text(settings.knobs.sender_sky.name())
        .show_ui(ui, |ui| {
            for option in crate::render::SenderSky::ALL {
                ui.selectable_value(&mut settings.knobs.sender_sky, option, option.name());
            }
        })
        .response
        .on_hover_text("march: the sky each sender sees; irradiance: its unoccluded sky; off: point lights only");
    ui.add(egui::Slider::new(&mut settings.exposure, 0.05..=16.0).logarithmic(true).text("exposure"));
    slider(ui, &mut settings.ambient, 0.0..=1.0, "ambient");
    ui.add(egui::Slider::new(&mut settings.sky_scale, 0.0..=16.0).text("sky scale"));
}

/// The point lights' count and seed.
fn lights_section(ui: &mut egui::Ui, state: &mut PanelState, actions: &mut Vec<Action>) {
    ui.label("Lights");
    let (lights, seed) = (state.lights, state.seed);
    ui.add(egui::Slider::new(&mut state.lights, 0..=64).text("count"));
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut state.seed).prefix("seed "));
        if ui.button("reseed").clicked() {
            state.seed = state.seed.wrapping_add(1);
        }
    });
    if (lights, seed) != (state.lights, state.seed) {
        actions.push(Action::Relight { lights: state.lights, seed: state.seed });
    }
}

/// The sky folders under `skyboxes/`, and fields for any sky or model path.
fn files_section(ui: &mut egui::Ui, state: &mut PanelState, actions: &mut Vec<Action>) {
    ui.label("Sky: folder or panorama (or drop one on the window)");
    let combo = egui::ComboBox::from_id_salt("skies").selected_text(state.sky_name.clone()).show_ui(ui, |ui| {
        for folder in &state.sky_folders {
            let name = folder.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            // A panorama's sky is named after the file without its extension.
            let stem = folder.file_stem().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            let current = name == state.sky_name || (folder.is_file() && stem == state.sky_name);
            if ui.selectable_label(current, name).clicked() {
                actions.push(Action::LoadSky(folder.clone()));
            }
        }
    });
    if combo.response.clicked() {
        state.sky_folders = super::loader::skybox_folders();
    }
    if let Some(path) = path_field(ui, &mut state.sky_path, "sky folder or panorama.hdr") {
        actions.push(Action::LoadSky(path));
    }
    ui.label(format!("Model: {} (or drop one on the window)", crate::scene::files::model_extensions()));
    if let Some(path) = path_field(ui, &mut state.model_path, "path/to/model.obj or .glb") {
        actions.push(Action::LoadModel(path));
    }
}

/// The fly camera, the camera's reset, screenshots, and the view's command.
fn camera_section(ui: &mut egui::Ui, state: &PanelState, actions: &mut Vec<Action>) {
    let mut fly = state.fly;
    if ui
        .checkbox(&mut fly, "fly camera (F)")
        .on_hover_text("W A S D move, Q/E or Ctrl/Space down and up, Shift faster, drag to look")
        .changed()
    {
        actions.push(Action::ToggleFly);
    }
    ui.horizontal_wrapped(|ui| {
        if ui.button("reset camera (R)").clicked() {
            actions.push(Action::ResetCamera);
        }
        if ui.button("screenshot (F12)").clicked() {
            actions.push(Action::Screenshot);
        }
        if ui.button("compare modes (C)").clicked() {
            actions.push(Action::Compare);
        }
    });
    ui.horizontal(|ui| {
        ui.label("This view headless:");
        if ui.button("copy command (P)").clicked() {
            actions.push(Action::CopyCommand);
        }
    });
    ui.add(egui::Label::new(egui::RichText::new(&state.command).monospace().small()).wrap());
}

/// Each pass's GPU time and the frame's.
fn timings_section(ui: &mut egui::Ui, state: &PanelState) {
    ui.label(format!("GPU time per pass ({})", state.timing_source));
    egui::Grid::new("timings").num_columns(2).show(ui, |ui| {
        for (name, ms) in &state.timings {
            ui.label(*name);
            ui.label(format!("{ms:.2} ms"));
            ui.end_row();
        }
        if !state.timings.is_empty() {
            ui.label("all passes");
            ui.label(format!("{:.2} ms", state.timings.iter().map(|(_, ms)| ms).sum::<f64>()));
            ui.end_row();
        }
        // Frames are drawn only when something changes, so this is how long one frame takes
        // from encoding to the screen (the GPU's work included), not a frame rate.
        ui.label("frame (wall)");
        ui.label(format!("{:.2} ms", state.frame_ms));
        ui.end_row();
    });
}
