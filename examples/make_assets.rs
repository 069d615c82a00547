//! Writes the repository's generated assets: the default scene (`models/cornell/`) and the three
//! skies (`skyboxes/day`, `skyboxes/redblue`, `skyboxes/sun`). Run from the repository root:
//! `cargo run --example make_assets`.

use std::path::Path;

use ssdo::scene::{builtin, Skybox};

fn main() -> anyhow::Result<()> {
    builtin::write_obj(&builtin::cornell()?, Path::new("models/cornell/cornell.obj"))?;
    builtin::write_skybox(&Skybox::from_fn("day", 128, builtin::day_sky), Path::new("skyboxes/day"), false)?;
    let mut redblue = Skybox::from_fn("redblue", 32, |_| glam::Vec3::ZERO);
    for (face, texels) in redblue.faces.iter_mut().enumerate() {
        texels.fill(builtin::redblue_face(face).into());
    }
    builtin::write_skybox(&redblue, Path::new("skyboxes/redblue"), false)?;
    builtin::write_skybox(&Skybox::from_fn("sun", 64, builtin::sun_sky), Path::new("skyboxes/sun"), true)?;
    println!("wrote models/cornell and skyboxes/day, skyboxes/redblue, skyboxes/sun");
    Ok(())
}
