//! Presets: the knobs (`crate::knobs`: the settings that trade error for time, the radius and the
//! thickness as multiples of the scene's), with what `ssdo tune` measured of them, as
//! a small JSON file every front end loads (`--preset FILE`), and the built-in quality levels
//! (`--quality`), which are tune's picks on the default scene.
//!
//! The file (`"ssdo_preset": 1`) holds `name`, `mode` (what it was tuned for), `settings` (each
//! key optional: a missing one keeps its default; an unknown one is an error) and, when tune wrote
//! it, `measured`: the device, scene, size, lights, budget and the figures. Numbers round-trip
//! exactly (JSON keeps every digit of an f32 and an f64).

use std::path::Path;

use serde_json::{json, Map, Value};

use crate::knobs::Knobs;
use crate::render::Mode;
use crate::text::num;
use crate::{Error, Result};

/// The version of the file format this build writes and reads.
pub const FORMAT: u64 = 1;

/// The largest preset file read: one that tune writes is under a kilobyte.
pub const MAX_PRESET_BYTES: u64 = 64 << 10;

/// What tune measured of a preset, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    /// The adapter, as `Gpu::describe` names it.
    pub device: String,
    /// The scene's name or model file, and its sky.
    pub scene: String,
    pub size: (u32, u32),
    pub lights: usize,
    /// The budget asked for (`None`: tune was given a target error only).
    pub budget_ms: Option<f64>,
    /// Median GPU milliseconds of a frame (on the first view).
    pub ms: f64,
    /// The Off frame's milliseconds in the same run (a scale that travels between devices).
    pub off_ms: f64,
    /// Errors against the ray-traced truth, averaged over the views.
    pub hdr_rmse: f64,
    pub do_rmse: Option<f64>,
    pub flip: f64,
    pub views: usize,
    /// Frames timed for `ms`.
    pub frames_timed: usize,
    pub date: String,
}

/// A named set of [`Knobs`] for a mode, with its measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct Preset {
    pub name: String,
    pub mode: Mode,
    pub knobs: Knobs,
    pub measured: Option<Measured>,
}

impl Measured {
    fn json(&self) -> Value {
        json!({
            "device": self.device,
            "scene": self.scene,
            "size": [self.size.0, self.size.1],
            "lights": self.lights,
            "budget_ms": self.budget_ms,
            "ms": self.ms,
            "off_ms": self.off_ms,
            "hdr_rmse": self.hdr_rmse,
            "do_rmse": self.do_rmse,
            "flip": self.flip,
            "views": self.views,
            "frames_timed": self.frames_timed,
            "date": self.date,
        })
    }

    fn from_json(v: &Value, at: &Reader) -> Result<Self> {
        let o = at.object(v, "measured")?;
        let keys = [
            "device",
            "scene",
            "size",
            "lights",
            "budget_ms",
            "ms",
            "off_ms",
            "hdr_rmse",
            "do_rmse",
            "flip",
            "views",
            "frames_timed",
            "date",
        ];
        at.only(o, "measured", &keys)?;
        let get = |key: &str| o.get(key).ok_or_else(|| at.error(&format!("measured.{key} is missing")));
        let text = |key: &str| at.text(get(key)?, &format!("measured.{key}"));
        let number = |key: &str| at.number(get(key)?, &format!("measured.{key}"));
        let optional = |key: &str| match o.get(key) {
            None | Some(Value::Null) => Ok(None),
            Some(v) => at.number(v, &format!("measured.{key}")).map(Some),
        };
        let whole = |key: &str| -> Result<usize> {
            get(key)?.as_u64().map(|n| n as usize).ok_or_else(|| at.bad(&format!("measured.{key}"), "a whole number"))
        };
        let size = match get("size")?.as_array().map(|a| a.iter().map(Value::as_u64).collect::<Vec<_>>()) {
            Some(s) if s.len() == 2 && s.iter().all(|v| v.is_some_and(|n| (1..=65536).contains(&n))) => {
                (s[0].unwrap_or(1) as u32, s[1].unwrap_or(1) as u32)
            }
            _ => return Err(at.bad("measured.size", "[width, height]")),
        };
        Ok(Self {
            device: text("device")?,
            scene: text("scene")?,
            size,
            lights: whole("lights")?,
            budget_ms: optional("budget_ms")?,
            ms: number("ms")?,
            off_ms: number("off_ms")?,
            hdr_rmse: number("hdr_rmse")?,
            do_rmse: optional("do_rmse")?,
            flip: number("flip")?,
            views: whole("views")?,
            frames_timed: whole("frames_timed")?,
            date: text("date")?,
        })
    }
}

impl Preset {
    pub fn json(&self) -> Value {
        let mut o = Map::new();
        o.insert("ssdo_preset".into(), json!(FORMAT));
        o.insert("name".into(), json!(self.name));
        o.insert("mode".into(), json!(self.mode.name()));
        o.insert("settings".into(), self.knobs.json());
        if let Some(m) = &self.measured {
            o.insert("measured".into(), m.json());
        }
        Value::Object(o)
    }

    /// The file's text: pretty JSON with a final newline.
    pub fn to_text(&self) -> String {
        let mut text = serde_json::to_string_pretty(&self.json()).expect("JSON of numbers and strings");
        text.push('\n');
        text
    }

    /// Reads a preset from `text`; `path` names it in errors.
    pub fn parse(path: &Path, text: &str) -> Result<Self> {
        let at = Reader { path };
        // A byte-order mark, which some editors write at the start of UTF-8, is not JSON's.
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let value: Value = serde_json::from_str(text).map_err(|e| at.error(&format!("not a preset (JSON: {e})")))?;
        let o = at.object(&value, "the file")?;
        // The format's number, as a whole number however it is written (1, 1.0, 1e0).
        match o.get("ssdo_preset").map(|v| (v, v.as_f64())) {
            Some((_, Some(n))) if n == FORMAT as f64 => {}
            Some((_, Some(n))) => {
                return Err(at
                    .error(&format!("ssdo_preset: preset format {}; this build reads format {FORMAT}", num(n as f32))))
            }
            Some((v, None)) => return Err(at.bad("ssdo_preset", &format!("the format number {FORMAT}, not {v}"))),
            None => return Err(at.error("not a preset (no \"ssdo_preset\": 1)")),
        }
        at.only(o, "the file", &["ssdo_preset", "name", "mode", "settings", "measured"])?;
        let name = match o.get("name") {
            Some(v) => at.text(v, "name")?,
            None => path.file_stem().map_or_else(String::new, |s| crate::text::bounded_name(&s.to_string_lossy())),
        };
        let mode = match o.get("mode") {
            Some(v) => at.parse::<Mode>(v, "mode")?,
            None => Mode::Ssdo,
        };
        let knobs = match o.get("settings") {
            Some(v) => Knobs::from_json(at.object(v, "settings")?).map_err(|problem| at.error(&problem))?,
            None => Knobs::default(),
        };
        let measured = o.get("measured").map(|v| Measured::from_json(v, &at)).transpose()?;
        Ok(Self { name, mode, knobs, measured })
    }

    /// Reads the preset file at `path`: a regular file of at most [`MAX_PRESET_BYTES`] in
    /// UTF-8 (a FIFO, a device or a huge file is refused before it is read).
    pub fn load(path: &Path) -> Result<Self> {
        let bytes = crate::scene::files::read_bounded(path, MAX_PRESET_BYTES).map_err(|p| Error::input(path, p))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            Error::input(path, format!("not a preset (not UTF-8 text: byte {} is not)", e.utf8_error().valid_up_to()))
        })?;
        Self::parse(path, &text)
    }

    /// The preset a command's flags name: `--preset FILE`, else a `--quality` level, else none.
    pub fn chosen(file: Option<&Path>, level: Option<Quality>) -> Result<Option<Self>> {
        match (file, level) {
            (Some(path), _) => Self::load(path).map(Some),
            (None, Some(level)) => Ok(Some(level.preset())),
            (None, None) => Ok(None),
        }
    }

    /// Writes the preset to `path` (a temporary name, then renamed).
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::output::write_atomic(path, self.to_text().as_bytes())
    }

    /// A warning when the figures were measured on another device or at another size than
    /// `device` and `size`: they say little about this run's time.
    pub fn elsewhere(&self, device: &str, size: (u32, u32)) -> Option<String> {
        let m = self.measured.as_ref()?;
        let mut differences = Vec::new();
        if m.device != device {
            differences.push(format!("on {} (this run: {device})", m.device));
        }
        if m.size != size {
            differences.push(format!("at {}x{} (this run: {}x{})", m.size.0, m.size.1, size.0, size.1));
        }
        (!differences.is_empty()).then(|| {
            format!(
                "preset '{}': its figures were measured {}; its time and error may differ here",
                self.name,
                differences.join(" and ")
            )
        })
    }
}

/// Reads a preset's JSON, naming the file and the key in every error.
struct Reader<'a> {
    path: &'a Path,
}

impl Reader<'_> {
    fn error(&self, problem: &str) -> Error {
        Error::input(self.path, problem)
    }

    fn bad(&self, key: &str, expected: &str) -> Error {
        self.error(&format!("{key}: expected {expected}"))
    }

    fn object<'v>(&self, v: &'v Value, key: &str) -> Result<&'v Map<String, Value>> {
        v.as_object().ok_or_else(|| self.bad(key, "an object"))
    }

    /// Unknown keys are errors: a misspelt setting would otherwise be silently ignored.
    fn only(&self, o: &Map<String, Value>, key: &str, known: &[&str]) -> Result<()> {
        match o.keys().find(|k| !known.contains(&k.as_str())) {
            Some(k) => Err(self.error(&format!("{key}: unknown key '{k}' (known: {})", known.join(", ")))),
            None => Ok(()),
        }
    }

    fn parse<T: std::str::FromStr<Err = Error>>(&self, v: &Value, key: &str) -> Result<T> {
        let text = v.as_str().ok_or_else(|| self.bad(key, "a name"))?;
        text.parse().map_err(|e: Error| self.error(&format!("{key}: {e}")))
    }

    /// A string of one line and at most [`crate::text::MAX_NAME_CHARS`] characters.
    fn text(&self, v: &Value, key: &str) -> Result<String> {
        let text = v.as_str().ok_or_else(|| self.bad(key, "a string"))?;
        match crate::text::name_problem(text) {
            Some(problem) => Err(self.error(&format!("{key}: {problem}"))),
            None => Ok(text.to_owned()),
        }
    }

    fn number(&self, v: &Value, key: &str) -> Result<f64> {
        v.as_f64().filter(|n| n.is_finite()).ok_or_else(|| self.bad(key, "a number"))
    }
}

/// The built-in quality levels: `ssdo tune`'s picks on the default scene (cornell, 320x240, 8
/// lights, SSDO, three views) at 2 (low), 3 (medium) and 8 (ultra) Off frames, on the machine named in
/// docs/quality.md. `High` is the default settings (what the report picked); the table that made
/// the others, and how to make it again, is in docs/quality.md.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quality {
    Low,
    Medium,
    High,
    Ultra,
}

impl Quality {
    pub const ALL: [Quality; 4] = [Quality::Low, Quality::Medium, Quality::High, Quality::Ultra];

    pub fn name(self) -> &'static str {
        match self {
            Quality::Low => "low",
            Quality::Medium => "medium",
            Quality::High => "high",
            Quality::Ultra => "ultra",
        }
    }

    /// The level's knobs.
    pub fn knobs(self) -> Knobs {
        let default = Knobs::default();
        match self {
            // No bounce, no blur: one slice of four steps a side, the radius a half octave up.
            Quality::Low => Knobs {
                slices: 1,
                steps: 4,
                radius_scale: std::f32::consts::SQRT_2,
                blur: false,
                indirect_strength: 0.0,
                ..default
            },
            Quality::Medium => Knobs { slices: 1, steps: 8, blur: false, ..default },
            Quality::High => default,
            // Tune's pick, and the far side layer, which tune measuring cornell alone does not
            // take at the default radius (3% worse there); at this radius it is better on every
            // report scene, and it orders ultra after high on stairs (docs/quality.md).
            Quality::Ultra => Knobs { steps: 24, radius_scale: 2.0, far_side: true, ..default },
        }
    }

    /// The level as a preset (the figures are in docs/quality.md, not carried here: they were
    /// measured on one machine and would mislead on another).
    pub fn preset(self) -> Preset {
        Preset { name: format!("quality {}", self.name()), mode: Mode::Ssdo, knobs: self.knobs(), measured: None }
    }
}

crate::error::named_choice!(Quality, "quality level", Quality::ALL.map(|q| (q.name(), q)));
