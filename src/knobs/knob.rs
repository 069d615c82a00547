//! What one knob does with its declaration: where it means anything, its value as JSON and as
//! text, reading and checking a value, which of two settings costs more, and its rungs.

use serde_json::{json, Value as Json};

use super::table::{switch, Cost, Kind, Knob, Knobs, Rungs, Scope, Value};
use crate::render::variant::Sampler;
use crate::render::Mode;
use crate::text::num;

impl Knob {
    /// The value within range, or the error naming the flag that gave it (a count or a gain; a
    /// multiple comes from a preset, checked as it is read).
    pub fn check_flag(&self, knobs: &Knobs) -> crate::Result<()> {
        match (self.kind, (self.get)(knobs)) {
            (Kind::Count(c), Value::Count(n)) => c.check(n).map(drop),
            (Kind::Gain { range: (lo, hi) }, Value::Number(v)) => {
                crate::error::in_range(self.flag, v, lo, hi).map(drop)
            }
            _ => Ok(()),
        }
    }

    /// Whether the knob means anything for `knobs` in `mode` (`None`: in any mode).
    pub fn applies(&self, knobs: &Knobs, mode: Option<Mode>) -> bool {
        let marches = knobs.variant.decl().sampler == Sampler::March;
        let directional = mode.is_none_or(|m| m.declaration().directional_occlusion);
        match self.scope {
            Scope::All => true,
            Scope::Points => !marches,
            Scope::March => marches,
            Scope::MarchDirectional => marches && directional,
            Scope::Directional => directional,
            Scope::Bounce => directional && knobs.indirect_strength > 0.0,
            Scope::FarSide => directional && knobs.indirect_strength > 0.0 && knobs.far_side,
        }
    }

    /// The value as a preset's JSON holds it.
    pub(super) fn json(&self, knobs: &Knobs) -> Json {
        match (self.get)(knobs) {
            Value::Count(n) => json!(n),
            Value::Switch(b) => json!(b),
            Value::Number(x) => json!(x),
            Value::Choice(name) => json!(name),
        }
    }

    /// The value as text (tune's CSV, a flag's value).
    pub fn text(&self, knobs: &Knobs) -> String {
        match (self.get)(knobs) {
            Value::Count(n) => n.to_string(),
            Value::Switch(b) => b.to_string(),
            Value::Number(x) => x.to_string(),
            Value::Choice(name) => name.to_string(),
        }
    }

    /// The value of `json` for this knob, or the problem naming its key (`settings.KEY: …`).
    pub(super) fn read(&self, json: &Json) -> std::result::Result<Value, String> {
        let expected = |what: &str| format!("settings.{}: expected {what}", self.key);
        match self.kind {
            Kind::Count(_) => json.as_u64().map(|n| Value::Count(n as usize)).ok_or_else(|| expected("a whole number")),
            Kind::Switch => json.as_bool().map(Value::Switch).ok_or_else(|| expected("true or false")),
            Kind::Multiple { .. } | Kind::Gain { .. } => json
                .as_f64()
                .filter(|x| x.is_finite())
                .map(|x| Value::Number(x as f32))
                .ok_or_else(|| expected("a number")),
            Kind::Choice { parse, .. } => {
                let text = json.as_str().ok_or_else(|| expected("a name"))?;
                parse(text).map(Value::Choice).map_err(|e| format!("settings.{}: {e}", self.key))
            }
        }
    }

    /// The value within range, or the problem naming the key and what is accepted.
    pub(super) fn check(&self, knobs: &Knobs) -> std::result::Result<(), String> {
        let key = self.key;
        match (self.kind, (self.get)(knobs)) {
            (Kind::Count(c), Value::Count(n)) if !c.range().contains(&n) => {
                Err(format!("settings.{key}: {n} is out of range; expected a whole number from {} to {}", c.min, c.max))
            }
            (Kind::Multiple { range: (lo, hi), .. } | Kind::Gain { range: (lo, hi) }, Value::Number(v))
                if !(v.is_finite() && (lo..=hi).contains(&v)) =>
            {
                Err(format!(
                    "settings.{key}: {} is out of range; expected a finite number from {} to {}",
                    num(v),
                    num(lo),
                    num(hi)
                ))
            }
            _ => Ok(()),
        }
    }

    /// Whether `a` and `b` differ in this knob where it means something in both, and if so
    /// whether `b` costs more a frame (the senders of a bounce against none are no difference:
    /// the bounce's strength is).
    pub(super) fn dearer(&self, a: &Knobs, b: &Knobs) -> Option<bool> {
        use std::cmp::Ordering;
        if !(self.applies(a, None) && self.applies(b, None)) {
            return None;
        }
        let rank = |v: Value| -> f64 {
            match (self.cost, v) {
                (Cost::AboveOne, Value::Count(n)) => f64::from(n > 1),
                (Cost::Ranked(names), Value::Choice(name)) => names.iter().position(|n| *n == name).unwrap_or(0) as f64,
                (_, Value::Count(n)) => n as f64,
                (_, Value::Switch(on)) => f64::from(on),
                (_, Value::Number(x)) => x as f64,
                (_, Value::Choice(_)) => 0.0,
            }
        };
        let order = rank((self.get)(a)).total_cmp(&rank((self.get)(b)));
        let order = match self.cost {
            Cost::Same => Ordering::Equal,
            Cost::Falls => order.reverse(),
            _ => order,
        };
        match order {
            Ordering::Less => Some(true),
            Ordering::Greater => Some(false),
            Ordering::Equal => None,
        }
    }

    /// The value on this knob's rungs that costs least a frame; `None` where tune leaves the knob
    /// or its cost does not move with it.
    pub(super) fn cheapest(&self) -> Option<Value> {
        let falls = self.cost == Cost::Falls;
        let value = match self.rungs {
            Rungs::Fixed => return None,
            Rungs::Counts(rungs) => Value::Count(if falls { rungs[rungs.len() - 1] } else { rungs[0] }),
            Rungs::Numbers(rungs) => Value::Number(if falls { rungs[rungs.len() - 1] } else { rungs[0] }),
            Rungs::Toggle => Value::Switch(falls),
            Rungs::Every => match self.cost {
                Cost::Ranked(names) => Value::Choice(names[0]),
                _ => return None,
            },
        };
        (self.cost != Cost::Same).then_some(value)
    }

    /// The settings one rung away on this knob, before they are made canonical.
    pub(super) fn steps_from(&self, knobs: &Knobs) -> Vec<Knobs> {
        let with = |v: Value| {
            let mut k = *knobs;
            (self.set)(&mut k, v);
            k
        };
        let current = (self.get)(knobs);
        let ladder: Vec<(f64, Value)> = match self.rungs {
            Rungs::Fixed => return Vec::new(),
            Rungs::Toggle => return vec![with(Value::Switch(!switch(current)))],
            Rungs::Every => {
                let Kind::Choice { names, .. } = self.kind else { return Vec::new() };
                return names()
                    .into_iter()
                    .filter(|&n| Value::Choice(n) != current)
                    .map(|n| with(Value::Choice(n)))
                    .collect();
            }
            Rungs::Counts(rungs) => rungs.iter().map(|&n| (n as f64, Value::Count(n))).collect(),
            Rungs::Numbers(rungs) => rungs.iter().map(|&x| (x as f64, Value::Number(x))).collect(),
        };
        let value = match current {
            Value::Count(n) => n as f64,
            Value::Number(x) => x as f64,
            _ => return Vec::new(),
        };
        // The rung at or below the value, and the ones either side of it.
        let at = ladder.iter().rposition(|&(r, _)| r <= value).unwrap_or(0);
        let below = if ladder[at].0 < value { Some(at) } else { at.checked_sub(1) };
        below.into_iter().chain([at + 1]).filter_map(|i| ladder.get(i)).map(|&(_, v)| with(v)).collect()
    }
}
