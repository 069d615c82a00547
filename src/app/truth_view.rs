//! The viewer's truth and error views: when the truth is traced anew (a view that has
//! settled), what is shown of it, the current mode's error against it, and the image F12 saves
//! of what is on screen (the split's second renderer is `split.rs`'s).

use std::sync::Arc;
use std::time::{Duration, Instant};

use image::RgbaImage;

use super::truth::{depth_at, Job, Rounds, Tracer, ViewKey, BYTES_PER_PIXEL};
use super::truth_ui::{Display, Side};
use super::view_state::{Measured, Shown, TruthState};
use super::Viewer;
use crate::headless::capture::capture_settled;
use crate::headless::readback::read_depth;
use crate::headless::truth::{colour_bar, error_scale, heat_map, ViewTruth};
use crate::{compare, Result};

/// How long a changed view must stay still before its truth is traced.
const SETTLE: Duration = Duration::from_millis(200);
/// How often the viewer looks for the truth's next round while it traces.
const POLL: Duration = Duration::from_millis(150);

impl Viewer {
    /// The truth's part of the event loop: starts, stops and reads the trace, measures the
    /// current mode against it; when to look again.
    pub(super) fn truth_tick(&mut self) -> Option<Instant> {
        let display = self.panel.truth.display;
        if self.truth.display != Some(display) {
            self.truth.display = Some(display);
            log::info!("view: {}", display.name());
        }
        let wanted = self.panel.truth.wants_truth();
        let hdr = self.panel.truth.display == Display::Error;
        if self.renderer.keeps_hdr() != hdr {
            self.renderer.keep_hdr(&self.gpu, hdr);
        }
        if !wanted {
            if self.truth.tracer.is_some() {
                let (model, display) = (self.truth.model.take(), self.truth.display);
                self.truth = TruthState { model, display, ..TruthState::default() };
                self.panel.truth.status.clear();
                self.panel.truth.errors.clear();
                self.panel.truth.bar = None;
            }
            return None;
        }
        if self.truth.tracer.is_none() {
            match Tracer::start() {
                Ok(tracer) => self.truth.tracer = Some(tracer),
                Err(e) => {
                    self.panel.say(format!("the truth cannot be traced: {e}"), true);
                    self.panel.truth.display = Display::Live;
                    return None;
                }
            }
        }
        let now = Instant::now();
        let key = self.truth_key();
        if self.truth.traced != Some(key) {
            if self.truth.settling.map(|(k, _)| k) != Some(key) {
                // The view changed: what was traced is of another; wait for this one to settle.
                if let Some(tracer) = &self.truth.tracer {
                    tracer.stop();
                }
                (self.truth.settling, self.truth.shown, self.truth.errors) = (Some((key, now)), None, None);
                self.truth.failure = None;
                self.panel.truth.status = vec!["the truth: waiting for the view to settle".into()];
                self.window.request_redraw();
                return Some(now + SETTLE);
            }
            let since = self.truth.settling.map_or(now, |(_, t)| t);
            // The G-buffer's depth must be this view's: a frame drawn with it, and finished.
            if now < since + SETTLE || self.pending.is_some() || self.drawn_camera != Some(key.camera) {
                return Some((since + SETTLE).max(now + Duration::from_millis(20)));
            }
            self.start_trace(key);
        }
        let latest = self.truth.tracer.as_ref().and_then(Tracer::latest).filter(|r| r.key == key);
        let newer = latest.filter(|r| self.truth.shown.as_ref().is_none_or(|s| s.rounds.rays() != r.rays()));
        if let Some(rounds) = newer {
            self.show_rounds(rounds);
            self.window.request_redraw();
        }
        if self.truth.shown.as_ref().is_some_and(|s| s.exposure != self.renderer.settings.exposure) {
            self.redisplay_truth();
            self.window.request_redraw();
        }
        self.measure_if_due();
        self.truth_status();
        let done = self.truth.shown.as_ref().is_some_and(|s| s.rounds.next_doubling().is_none());
        (!done).then_some(now + POLL)
    }

    /// What the truth of the view on screen depends on.
    fn truth_key(&self) -> ViewKey {
        let (w, h) = self.renderer.size();
        let d = self.panel.truth.divisor();
        let s = &self.renderer.settings;
        ViewKey {
            camera: self.view_camera(),
            scene: self.scene_number,
            size: ((w / d).max(1), (h / d).max(1)),
            sky_scale: s.sky_scale,
            ambient: s.ambient,
            radius: self.renderer.radius(),
        }
    }

    /// Sends the view `key` to the tracer, with the G-buffer's depth of the frame just drawn.
    fn start_trace(&mut self, key: ViewKey) {
        (self.truth.traced, self.truth.settling) = (Some(key), None);
        let (w, h) = key.size;
        let bytes = w as u64 * h as u64 * BYTES_PER_PIXEL;
        let within = crate::budget::check(crate::budget::Share::Targets, bytes, || {
            format!("the truth at {w}x{h} (choose a smaller share of the view)")
        });
        let depth = within
            .map_err(|e| e.to_string())
            .and_then(|()| read_depth(&self.gpu, &self.renderer.targets().depth().texture).map_err(|e| e.to_string()));
        let depth = match depth {
            Ok(depth) => depth_at(&depth, self.renderer.size(), key.size),
            Err(problem) => {
                self.truth.failure = Some(problem);
                return;
            }
        };
        let model = match &self.truth.model {
            Some((n, model)) if *n == self.scene_number => model.clone(),
            _ => {
                let model = Arc::new(self.scene.model.clone());
                self.truth.model = Some((self.scene_number, model.clone()));
                model
            }
        };
        let (lights, rig, sky) = (self.scene.lights.clone(), self.scene.rig, self.sky.clone());
        if let Some(tracer) = &self.truth.tracer {
            tracer.trace(Job { key, model, sky, lights, rig, depth, seed: self.panel.seed });
        }
    }

    /// Makes the truth of `rounds` the one on screen.
    fn show_rounds(&mut self, rounds: Arc<Rounds>) {
        let seconds = rounds.elapsed.as_secs_f64();
        let made = ViewTruth::from_traces(
            (&rounds.a, &rounds.b),
            rounds.key.ambient,
            &self.sky,
            rounds.rays_per_trace,
            seconds,
        );
        match made {
            Ok(truth) => {
                let (w, h) = rounds.key.size;
                log::info!(
                    "the truth: {} rays a pixel at {w}x{h} after {seconds:.1} s, noise HDR {:.4}",
                    rounds.rays(),
                    truth.noise_hdr()
                );
                let exposure = self.renderer.settings.exposure;
                let image = truth.overlay(exposure);
                let texture = self.texture("ssdo_truth", &image);
                self.truth.shown = Some(Shown { rounds, truth, exposure, image, texture });
            }
            Err(e) => self.truth.failure = Some(e.to_string()),
        }
    }

    /// The shown truth displayed again at the exposure of now.
    fn redisplay_truth(&mut self) {
        let exposure = self.renderer.settings.exposure;
        let Some(shown) = &self.truth.shown else { return };
        let image = shown.truth.overlay(exposure);
        let texture = self.texture("ssdo_truth", &image);
        if let Some(shown) = &mut self.truth.shown {
            (shown.exposure, shown.image, shown.texture) = (exposure, image, texture);
        }
    }

    fn texture(&self, name: &str, image: &RgbaImage) -> egui::TextureHandle {
        let size = [image.width() as usize, image.height() as usize];
        let colour = egui::ColorImage::from_rgba_unmultiplied(size, image.as_raw());
        self.egui.egui_ctx().load_texture(name, colour, egui::TextureOptions::NEAREST)
    }

    /// Measures the current mode against the shown truth when the error view wants it and the
    /// frame has converged (a still view: the average the report measures).
    fn measure_if_due(&mut self) {
        let mode = self.renderer.settings.mode;
        let Some(shown) = &self.truth.shown else { return };
        let current = self.truth.errors.as_ref().is_some_and(|m| m.mode == mode && m.rays == shown.rounds.rays());
        let ready = !self.renderer.converging() && self.pending.is_none();
        if self.panel.truth.display != Display::Error || current || !ready || shown.truth.size() != self.renderer.size()
        {
            return;
        }
        let camera = self.view_camera();
        let measured = capture_settled(&self.gpu, &mut self.renderer, &camera)
            .and_then(|image| shown.truth.measure(&self.gpu, &self.renderer, mode, &image));
        let error = match measured {
            Ok(error) => error,
            Err(e) => {
                self.truth.failure = Some(e.to_string());
                return;
            }
        };
        let rays = shown.rounds.rays();
        // A new round of the truth sets the scale anew (its noise was part of the last one's);
        // another mode against the same round keeps it, so the modes' maps compare.
        let kept = self.truth.errors.as_ref().filter(|m| m.rays == rays).map(|m| m.scale);
        let scale = kept.unwrap_or_else(|| error_scale(std::slice::from_ref(&error)));
        let image = heat_map(&error.per_pixel, shown.truth.size(), scale);
        let texture = self.texture("ssdo_error", &image);
        if self.panel.truth.bar.is_none() {
            let bar = self.texture("ssdo_error_bar", &colour_bar(256));
            self.panel.truth.bar = Some((bar, scale));
        }
        if let Some((_, s)) = &mut self.panel.truth.bar {
            *s = scale;
        }
        self.truth.errors = Some(Measured { mode, rays, error, scale, image, texture });
        self.window.request_redraw();
    }

    /// The panel's lines: the rays so far, the next doubling, the noise, the errors.
    fn truth_status(&mut self) {
        let threads = self.truth.tracer.as_ref().map_or(0, |t| t.threads);
        let mut status = Vec::new();
        let mut errors = Vec::new();
        if let Some(problem) = &self.truth.failure {
            status.push(format!("no truth for this view: {problem}"));
        } else if let Some(shown) = &self.truth.shown {
            let r = &shown.rounds;
            let (w, h) = r.key.size;
            status.push(format!(
                "the truth: {} rays a pixel at {w}x{h} in {:.1} s ({threads} threads)",
                r.rays(),
                r.elapsed.as_secs_f64()
            ));
            status.push(match r.next_doubling() {
                Some(next) => format!("doubles in about {:.1} s", next.as_secs_f64()),
                None => "complete".into(),
            });
            status.push(format!("its noise: HDR RMSE {:.4}", shown.truth.noise_hdr()));
        } else if self.truth.traced.is_some() {
            status.push(format!("the truth: tracing its first rays ({threads} threads)"));
        }
        if self.panel.truth.display == Display::Error {
            let mode = self.renderer.settings.mode;
            match (&self.truth.shown, &self.truth.errors) {
                (Some(shown), Some(m)) if m.mode == mode => {
                    let noise = shown.truth.noise_hdr();
                    if noise < m.error.hdr_rmse {
                        errors.push(format!("{}: {}", mode.title(), m.error.summary()));
                    } else {
                        errors.push(format!(
                            "{}: the truth's noise ({noise:.4}) is above the error it measures ({:.4}): tracing on",
                            mode.title(),
                            m.error.hdr_rmse
                        ));
                    }
                }
                (Some(_), _) => errors.push("measuring once the frame has settled".into()),
                _ => {}
            }
        }
        (self.panel.truth.status, self.panel.truth.errors) = (status, errors);
    }

    /// Paints what the view shows over the frame: the truth, the error map, or the image right
    /// of the divider and the divider, within the view's `rect` (in points).
    pub(super) fn paint_view(&self, ctx: &egui::Context, rect: egui::Rect) {
        let painter = ctx.layer_painter(egui::LayerId::new(egui::Order::Background, egui::Id::unique("ssdo_view")));
        let whole = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
        let truth = self.truth.shown.as_ref().map(|s| s.texture.id());
        match self.panel.truth.display {
            Display::Live => {}
            Display::Truth => {
                if let Some(id) = truth {
                    painter.image(id, rect, whole, egui::Color32::WHITE);
                }
            }
            Display::Error => {
                if let Some(m) = &self.truth.errors {
                    painter.image(m.texture.id(), rect, whole, egui::Color32::WHITE);
                }
            }
            Display::Split(side) => {
                let d = self.panel.truth.divider.clamp(0.0, 1.0);
                let x = rect.left() + d * rect.width();
                let right = egui::Rect::from_min_max(egui::pos2(x, rect.top()), rect.max);
                let uv = egui::Rect::from_min_max(egui::pos2(d, 0.0), egui::pos2(1.0, 1.0));
                let id = match side {
                    Side::Truth => truth,
                    Side::Mode(_) => self.split.texture(),
                };
                if let Some(id) = id {
                    painter.image(id, right, uv, egui::Color32::WHITE);
                }
                let line = [egui::pos2(x, rect.top()), egui::pos2(x, rect.bottom())];
                painter.line_segment(line, egui::Stroke::new(2.0, egui::Color32::WHITE));
            }
        }
    }

    /// What the view shows, as an image of its size: the live frame settled, with the truth,
    /// the error map or the right of the divider over it.
    pub(super) fn screen_image(&mut self) -> Result<RgbaImage> {
        let camera = self.view_camera();
        let live = capture_settled(&self.gpu, &mut self.renderer, &camera)?;
        let display = self.panel.truth.display;
        let second = match display {
            Display::Split(Side::Mode(_)) => self.capture_second(&camera)?,
            _ => None,
        };
        let over = |top: Option<&RgbaImage>| top.map_or_else(|| live.clone(), |t| compare::overlay(&live, t));
        let truth = self.truth.shown.as_ref().map(|s| &s.image);
        Ok(match display {
            Display::Live => live.clone(),
            Display::Truth => over(truth),
            Display::Error => over(self.truth.errors.as_ref().map(|m| &m.image)),
            Display::Split(side) => {
                let right = match side {
                    Side::Truth => over(truth),
                    Side::Mode(_) => second.unwrap_or_else(|| live.clone()),
                };
                compare::split(&live, &right, self.panel.truth.divider)
            }
        })
    }

    /// The truth's figures for a comparison: the truth over `live` (an image of the view), and
    /// whether it is the current view's.
    pub(super) fn truth_for_compare(&self) -> Option<&ViewTruth> {
        let shown = self.truth.shown.as_ref()?;
        (shown.truth.size() == self.renderer.size() && Some(shown.rounds.key) == self.truth.traced)
            .then_some(&shown.truth)
    }

    /// The rays a pixel of each of the truth's traces, for the command that reproduces the view.
    pub(super) fn truth_rays(&self) -> Option<u32> {
        let shown = self.truth.shown.as_ref()?;
        self.panel.truth.wants_truth().then_some(shown.rounds.rays_per_trace)
    }
}
