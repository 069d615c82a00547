//! The panel's truth section: what the 3D view shows (the live frame, the truth, the current
//! mode's error against it, or two images split by a divider), the truth's progress and the
//! errors, with their colour bar.

use crate::render::Mode;

/// What the 3D view shows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Display {
    /// The current mode, live.
    Live,
    /// The ray-traced truth of the view (key G).
    Truth,
    /// The current mode's per-pixel error against the truth, a heat map (key X).
    Error,
    /// The current mode left of the divider, `Side` right of it (key V: the truth, then each
    /// mode in turn).
    Split(Side),
}

impl Display {
    /// "live", "truth", "error", "split with SSAO".
    pub fn name(self) -> String {
        match self {
            Display::Live => "live".into(),
            Display::Truth => "truth".into(),
            Display::Error => "error".into(),
            Display::Split(side) => format!("split with {}", side.label()),
        }
    }
}

/// The image right of the divider.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Side {
    Mode(Mode),
    Truth,
}

impl Side {
    pub fn label(self) -> &'static str {
        match self {
            Side::Mode(m) => m.title(),
            Side::Truth => "Truth",
        }
    }
}

/// The truth's size against the view's: 1, 1/2 or 1/4 of each side.
pub const FRACTIONS: [u32; 3] = [1, 2, 4];

/// What the panel keeps of the truth.
pub struct TruthPanel {
    pub display: Display,
    /// Where the divider stands, as a share of the view's width.
    pub divider: f32,
    /// The truth traced at the view's size divided by this (the error view always at 1).
    pub fraction: u32,
    /// The progress, one line each (the viewer writes them every frame the truth runs).
    pub status: Vec<String>,
    /// The errors of the current mode, or why they are not shown yet.
    pub errors: Vec<String>,
    /// The error map's colour bar and the error its right end stands for.
    pub bar: Option<(egui::TextureHandle, f32)>,
}

impl Default for TruthPanel {
    fn default() -> Self {
        Self { display: Display::Live, divider: 0.5, fraction: 1, status: Vec::new(), errors: Vec::new(), bar: None }
    }
}

impl TruthPanel {
    /// Whether the view needs the truth traced.
    pub fn wants_truth(&self) -> bool {
        matches!(self.display, Display::Truth | Display::Error | Display::Split(Side::Truth))
    }

    /// The truth's size divisor: the error view measures the view's own pixels.
    pub fn divisor(&self) -> u32 {
        if self.display == Display::Error {
            1
        } else {
            self.fraction
        }
    }

    /// The split view's next right side (key V): the truth, then each mode, then the live view.
    pub fn cycle_split(&mut self) {
        let sides: Vec<Side> = [Side::Truth].into_iter().chain(Mode::ALL.map(Side::Mode)).collect();
        self.display = match self.display {
            Display::Split(side) => match sides.iter().position(|s| *s == side) {
                Some(i) if i + 1 < sides.len() => Display::Split(sides[i + 1]),
                _ => Display::Live,
            },
            _ => Display::Split(Side::Truth),
        };
    }

    /// `display` on, or back to the live view if it is on already (a key pressed twice).
    pub fn toggle(&mut self, display: Display) {
        let same = std::mem::discriminant(&self.display) == std::mem::discriminant(&display);
        self.display = if same { Display::Live } else { display };
    }
}

/// Draws the section.
pub fn section(ui: &mut egui::Ui, state: &mut TruthPanel, mode: Mode) {
    ui.label("View (G truth, X error, V split)");
    ui.horizontal_wrapped(|ui| {
        let split = match state.display {
            Display::Split(side) => Display::Split(side),
            _ => Display::Split(Side::Truth),
        };
        for (display, label) in
            [(Display::Live, "live"), (Display::Truth, "truth"), (Display::Error, "error"), (split, "split")]
        {
            let on = std::mem::discriminant(&state.display) == std::mem::discriminant(&display);
            if ui.selectable_label(on, label).clicked() {
                state.display = display;
            }
        }
    });
    if let Display::Split(side) = &mut state.display {
        egui::ComboBox::from_label(format!("right of {}", mode.title())).selected_text(side.label()).show_ui(
            ui,
            |ui| {
                for choice in [Side::Truth].into_iter().chain(Mode::ALL.map(Side::Mode)) {
                    ui.selectable_value(side, choice, choice.label());
                }
            },
        );
        ui.add(egui::Slider::new(&mut state.divider, 0.0..=1.0).text("divider (drag it in the view)"));
    }
    if state.display != Display::Error {
        egui::ComboBox::from_label("truth's size").selected_text(format!("1/{} of the view", state.fraction)).show_ui(
            ui,
            |ui| {
                for f in FRACTIONS {
                    ui.selectable_value(&mut state.fraction, f, format!("1/{f} of the view"));
                }
            },
        );
    }
    for line in &state.status {
        ui.label(line);
    }
    for line in &state.errors {
        ui.label(egui::RichText::new(line).strong());
    }
    if let Some((bar, scale)) = &state.bar {
        let size = egui::vec2(ui.available_width(), 10.0);
        ui.add(egui::Image::new(bar).maintain_aspect_ratio(false).fit_to_exact_size(size));
        ui.horizontal(|ui| {
            ui.label("0");
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| ui.label(format!("{scale:.3}")));
        });
        ui.label("per-pixel error: RMS of the HDR channels");
    }
}
