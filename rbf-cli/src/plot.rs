//! `rbf plot`: a 2D model's curve with its constraints.

use std::path::PathBuf;

use clap::Args;
use rbf_core::AnyModel;
use rbf_render::{PlotSettings, plot_curve};

use crate::common::{read_text, write_atomically};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Draws the curve f = 0 and marks the constraints as in the paper's figures: boundary
constraints as circles, interior as +, exterior as −, normal constraints as spikes pointing
outward. --colour-map shades the plane by f (warm inside, cool outside).

Examples:
  rbf fit curve.txt --dim 2 -o curve.json && rbf plot curve.json -o curve.png
  rbf plot curve.json -o field.png --colour-map --width 800 --height 600";

#[derive(Args, Debug)]
pub(crate) struct PlotArgs {
    /// A 2D model file.
    model: PathBuf,
    /// PNG to write.
    #[arg(short, long, value_name = "OUT.png")]
    output: PathBuf,
    /// Image width in pixels.
    #[arg(long, default_value_t = 512)]
    width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 512)]
    height: u32,
    /// Shade the plane by the value of f.
    #[arg(long, alias = "colormap")]
    colour_map: bool,
}

pub(crate) fn run(args: &PlotArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.model.display().to_string();
    let model = match AnyModel::from_json(&read_text(&args.model)?)
        .map_err(|e| Failure::file(&source, &e))?
    {
        AnyModel::Two(m) => m,
        AnyModel::Three(_) => {
            return Err(Failure::new(
                USAGE,
                format!("{source} is a 3D model: draw it with `rbf render`"),
            ));
        }
    };
    let settings = PlotSettings {
        width: args.width,
        height: args.height,
        colour_map: args.colour_map,
        ..Default::default()
    };
    let image = plot_curve(&model.interpolant.view(), &model.constraints, &settings)
        .map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
    let png = image
        .to_png()
        .map_err(|e| Failure::new(BAD_INPUT, e.to_string()))?;
    write_atomically(&args.output, &png)?;
    if !quiet {
        eprintln!("wrote {}", args.output.display());
    }
    Ok(())
}
