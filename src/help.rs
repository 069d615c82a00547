//! The command line's help written from the declarations: each count's range and defaults from
//! its knob (`ssdo::knobs::KNOBS`), the report's sweeps from the counts, so a range is stated in
//! one place.

use crate::cli::{Cli, MAX_SWEEP};

impl Cli {
    /// Parses the command line, with the sampling counts' help texts written from their
    /// declarations (`render::variant`), so a range is stated in one place.
    pub(crate) fn try_parse_with_ranges() -> Result<Self, clap::Error> {
        use clap::{CommandFactory, FromArgMatches};
        use ssdo::knobs::{Kind, Knobs, KNOBS};
        use ssdo::render::{Count, Variant, SAMPLES, SLICES, STEPS};
        let range = |c: &Count| format!("{}-{}", c.min, c.max);
        // A count's default, and each variant's own where it differs ("16; classic 32").
        let defaults = |knob: &ssdo::knobs::Knob| {
            let default = knob.text(&Knobs::default());
            let others: Vec<String> = Variant::ALL
                .into_iter()
                .filter_map(|v| {
                    let own = knob.text(&Knobs::for_variant(v));
                    (own != default).then(|| format!("{v} {own}"))
                })
                .collect();
            std::iter::once(default).chain(others).collect::<Vec<_>>().join("; ")
        };
        // The counts' help and parsers from their knobs: a count that is no whole number (-1,
        // 2.5) is refused saying what the count accepts.
        let render_help = |mut command: clap::Command| {
            for knob in &KNOBS {
                let Kind::Count(c) = knob.kind else { continue };
                let help = format!("{}, {} [default: {}]", knob.help, range(&c), defaults(knob));
                let whole = move |s: &str| ssdo::spec::whole_number(s, (c.min, c.max));
                command = command.mut_arg(knob.flag, |a| a.value_parser(whole).help(help));
            }
            command
        };
        let mut command = Self::command();
        for name in ["view", "capture", "bench"] {
            command = command.mut_subcommand(name, render_help);
        }
        command = command.mut_subcommand("report", |c| {
            c.mut_arg("samples", |a| {
                a.help(format!(
                    "Sample counts of the points and classic variants to sweep, comma-separated (each {}, at most {MAX_SWEEP} counts)",
                    range(&SAMPLES)
                ))
            })
            .mut_arg("march", |a| {
                a.help(format!(
                    "Slices x steps of the march variant to sweep, comma-separated (slices {}, steps {}; at most {MAX_SWEEP})",
                    range(&SLICES),
                    range(&STEPS)
                ))
            })
        });
        Self::from_arg_matches(&command.try_get_matches()?)
    }
}
