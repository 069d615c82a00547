//! The help tells the truth about defaults: every `[default: X]` a flag's help states, where X
//! is a value the flag takes, gives the same settings and camera as leaving the flag out.
//! (Defaults stated in words, "a tenth of the scene's bounding radius", are not values.)

use clap::{CommandFactory, Parser};
use ssdo::render::Mode;
use ssdo::spec::{RenderArgs, SceneArgs};

#[derive(Parser)]
struct Flags {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    render: RenderArgs,
}

/// What the flags lead to: the settings, and the camera on the default scene.
fn outcome(args: &[&str], scene: &ssdo::scene::Scene) -> Option<String> {
    let flags = Flags::try_parse_from(std::iter::once("ssdo").chain(args.iter().copied())).ok()?;
    let settings = flags.render.settings(Mode::Ssdo).ok()?;
    let camera = flags.scene.camera(scene).ok()?;
    Some(format!("{settings:?} {camera:?}"))
}

#[test]
fn every_stated_default_is_the_default() {
    let model = ssdo::scene::load_model(None).unwrap();
    let scene = ssdo::scene::Scene::new(model, 8, 1);
    let unset = outcome(&[], &scene).expect("no flags parse");
    let mut checked = Vec::new();
    for arg in Flags::command().get_arguments() {
        let (Some(flag), Some(help)) = (arg.get_long(), arg.get_help()) else { continue };
        let help = help.to_string();
        let Some(stated) = help.split("[default: ").nth(1) else { continue };
        let value = stated.split([';', ']']).next().unwrap_or_default().trim();
        let flag = format!("--{flag}");
        // A value the flag takes; words are left out.
        let Some(given) = outcome(&[&flag, value], &scene) else { continue };
        assert_eq!(given, unset, "{flag} says [default: {value}], but giving it changes the outcome");
        checked.push(flag);
    }
    // The help of --sender-sky once said march where the default is last-frame.
    for expected in ["--sender-sky", "--indirect-strength", "--ambient", "--yaw", "--pitch", "--far"] {
        assert!(checked.iter().any(|f| f == expected), "{expected} not checked: {checked:?}");
    }
}
