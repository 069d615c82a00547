//! Writes a textured stand-in for a scanned character into a folder (default `figure/`): the
//! benchmark room's built-in figure (`ssdo::scene::room::figure`, 50,000 triangles) with its UVs
//! tiled 4 × 8 times, and 2048x2048 diffuse and specular maps of a fine pattern that aliases without
//! mip maps. It times the G-buffer on a textured model (README, Speed):
//!
//! ```sh
//! cargo run --release --example textured_figure -- /tmp/figure
//! cargo run --release -- bench --scene room --model /tmp/figure/figure.obj --variant classic --lights 1 --radius 0.5
//! ```

use std::path::PathBuf;

use ssdo::scene::{builtin, room};

/// Texture repeats around and along the figure.
const TILING: [f32; 2] = [4.0, 8.0];
const SIDE: u32 = 2048;

fn main() -> anyhow::Result<()> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "figure".into()));
    std::fs::create_dir_all(&dir)?;
    let mut figure = room::figure(room::DEFAULT_FIGURE_TRIANGLES)?;
    for v in &mut figure.vertices {
        v.uv = [v.uv[0] * TILING[0], v.uv[1] * TILING[1]];
    }
    figure.materials[0].name = "skin".into();
    (figure.materials[0].specular, figure.materials[0].shininess) = ([0.5; 3], 32.0);
    let obj = dir.join("figure.obj");
    builtin::write_obj(&figure, &obj)?;
    // The maps, named in the material file write_obj made.
    let mtl = obj.with_extension("mtl");
    let text = std::fs::read_to_string(&mtl)? + "map_Kd diffuse.png\nmap_Ks specular.png\n";
    ssdo::output::write_atomic(&mtl, text.as_bytes())?;
    let diffuse = image::RgbImage::from_fn(SIDE, SIDE, |x, y| {
        if (x * 7 + y * 13) % 11 == 0 {
            image::Rgb([60, 60, 60])
        } else {
            image::Rgb([200, (120 + 80 * ((x / 3 + y / 3) % 2)) as u8, 90])
        }
    });
    diffuse.save(dir.join("diffuse.png"))?;
    image::GrayImage::from_fn(SIDE, SIDE, |x, y| image::Luma([255 * ((x ^ y) & 1) as u8]))
        .save(dir.join("specular.png"))?;
    println!("wrote {} ({} triangles) with 2048x2048 maps", obj.display(), figure.triangle_count());
    Ok(())
}
