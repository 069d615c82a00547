//! The switch knobs as a person turns them, from their declarations: each is a flag that turns
//! it from its default (`--no-blur`, `--full-res`, `--depth-pyramid`, `--far-side`), a checkbox
//! in the panel and, where it is not at its default, a flag of the reproducing command line. A
//! new switch is its row in `KNOBS` and its field.

use clap::{Arg, ArgAction, ArgMatches, Command};

use super::table::{switch, Kind, Knob, Knobs, Value, KNOBS};

/// The switch knobs, in the table's order.
pub fn switches() -> impl Iterator<Item = &'static Knob> {
    KNOBS.iter().filter(|k| matches!(k.kind, Kind::Switch))
}

impl Knob {
    /// A switch's default (the same in every variant).
    pub fn default_switch(&self) -> bool {
        switch((self.get)(&Knobs::default()))
    }

    /// Whether a switch is on in `knobs`.
    pub fn is_on(&self, knobs: &Knobs) -> bool {
        switch((self.get)(knobs))
    }

    /// Turns a switch on or off in `knobs`, every other knob as it was.
    pub fn turn(&self, knobs: &mut Knobs, on: bool) {
        (self.set)(knobs, Value::Switch(on));
    }

    /// The flag's help: what the knob does, and what the flag does to it.
    fn flag_help(&self) -> String {
        match self.default_switch() {
            true => format!("{} [default: on; the flag turns it off]", self.help),
            false => format!("{} [default: off]", self.help),
        }
    }
}

/// The switches a command line turned from their defaults, by key: one flag each, declared by
/// its knob.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SwitchFlags(Vec<&'static str>);

impl SwitchFlags {
    /// Turns each switch given from its default in `knobs` (a preset's, or the defaults).
    pub fn apply(&self, knobs: &mut Knobs) {
        for knob in switches().filter(|k| self.0.contains(&k.key)) {
            (knob.set)(knobs, Value::Switch(!knob.default_switch()));
        }
    }
}

impl clap::FromArgMatches for SwitchFlags {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        Ok(Self(switches().filter(|k| matches.get_flag(k.flag)).map(|k| k.key).collect()))
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Args for SwitchFlags {
    fn augment_args(command: Command) -> Command {
        switches().fold(command, |c, knob| {
            c.arg(Arg::new(knob.flag).long(knob.flag).action(ArgAction::SetTrue).help(knob.flag_help()))
        })
    }

    fn augment_args_for_update(command: Command) -> Command {
        Self::augment_args(command)
    }
}
