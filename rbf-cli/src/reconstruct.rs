//! `rbf reconstruct`: a scan (a point cloud, with or without normals) to a closed mesh, and
//! optionally the model behind it.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use rbf_convert::{ReconstructSettings, ScanSurface, scan_surface};
use rbf_mesh::{PointCloud, write_mesh};

use crate::common::{read_text, spinner, write_atomically};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Points given twice are dropped, then outliers (a mean distance to the 20 nearest points more
than 2.5 deviations above the cloud's, and 1.5 times its neighbours' or 8 times the cloud's
median: a region scanned more sparsely than the rest is kept), normals estimated from local planes where the cloud has none (16 neighbours;
more, up to 128, for a cloud scanned in lines, slices or profiles farther apart than 16 reach,
whose spread is then thinned as many times over) and
every normal oriented consistently and outward (a minimum spanning tree of the neighbour graph;
given normals are checked the same way and flipped ones fixed); then patches of them, cut where
neighbouring normals turn by more than 35° (on a clean scan, again at 26°), are reversed as a
whole where the winding number of all the other points says they point inward at their own
probes. A noisy scan (noise above 1e-3 of the box, or above 4 % of the points' own spacing:
the summary says \"points smoothed\") is smoothed first: its noise is measured on
neighbourhoods grown until they reach four times it, each point moves
onto the plane of such a neighbourhood (onto a quadric where it spreads beyond twice that
reach, in a sparsely scanned region), and each normal's sign is checked by the winding
number of the other points (at probes inside and outside along it; where the two together see
a negative field, on a closed scan, the whole part around it points in, as a foot reached the
wrong way through where it touches the body, and it turns), then voted on by coarse fits to
them (in the first round only), and the patches are cut and judged again (up to three
rounds); a lone normal against neighbours that agree is turned to them; last, lines of sight:
where the scan stops rays along a normal (most of a cone about it) and rays against it leave
the box, it turns (a thin blade's two sheets facing the same way; on a clean scan only in a
second attempt, made when the first fit still strays outside nearly everywhere after a round
of outside constraints, or its mesh comes out open). Normals more than 60°
from their neighbours' are left out. Each inside point of a normal constraint goes only as deep as it stays nearest
its own point, so that thin walls are not pierced. An even spread of
the points then carries normal constraints in one smoothing fit (λ, --smoothing): on a clean
scan 1.5·10⁴ of them (twice as fine where two sheets face each other within three of its
spacings) and a light λ (3e-5), which follows the points closely but does not close narrow
crevices over; on a noisy one 10⁴ of its smoothed points and a λ that grows with the
noise, which passes through its middle. --tolerance T asks for a greedy fit instead: a subset
of the points chosen greedily carries the constraints until the surface passes within T of
every point (up to --max-centres; films may close crevices over). Holes are closed by the implicit surface itself, and where f is not
negative just outside the scan (around it, and beside each point where the winding number of
the oriented points does not say inside), outside constraints hold it down. The mesh is polygonized with cubes about one point spacing
wide (thin parts keep their topology), without bubbles that no point is near, crumbs smaller
than 20 points' worth of area, or closed cavities inside the solid (which no scanner sees: the
inside of an opening narrower than a point spacing, closed over); --trim D keeps only the surface within D of the points (an open
scan's own surface, not what closes it).

Clouds: .ply (ASCII or binary, with or without nx ny nz), .npy (N × 3 or N × 6), .xyz or .txt
(x y z or x y z nx ny nz per line). Meshes out: .obj, .ply, .stl.

Examples:
  rbf reconstruct scan.ply -o surface.obj
  rbf reconstruct scan.xyz -o surface.ply --model scan.json --resolution 256
  rbf reconstruct noisy.npy -o smooth.stl --smoothing 1e-3   (smoother than the default)
  rbf reconstruct noisy.npy -o close.stl --tolerance 0.005   (greedy, within 0.5 % of the box)
  rbf reconstruct face.ply -o face.obj --trim 2.5   (an open scan, in millimetres)";

#[derive(Args, Debug)]
pub(crate) struct ReconstructArgs {
    /// Point cloud: .ply, .npy, .xyz or .txt.
    cloud: PathBuf,
    /// Mesh to write: .obj, .ply or .stl.
    #[arg(short, long, value_name = "MESH")]
    output: PathBuf,
    /// Also write the fitted model (JSON, as `rbf fit` writes).
    #[arg(long, value_name = "MODEL")]
    model: Option<PathBuf>,
    /// Cubes across the longest side [default: from the points' spacing, 96 to 384].
    #[arg(long, value_name = "N")]
    resolution: Option<usize>,
    /// Fit greedily until the surface passes within T of every point, as a fraction of the
    /// box's longest side [default: a smoothing fit; its misses are reported against three
    /// times the measured noise, at least 2.5e-3].
    #[arg(long, value_name = "T")]
    tolerance: Option<f64>,
    /// The most points that carry constraints, a cap [default: an even spread of 15000 on a
    /// clean scan, made finer where two sheets run close; 10000 on a noisy one; 8000 in a
    /// greedy fit (--tolerance)].
    #[arg(long, value_name = "N")]
    max_centres: Option<usize>,
    /// λ of the smoothing fit, for a box whose longest side is 2: larger is smoother, smaller
    /// follows the points more closely [default: from the measured noise: 3e-5 up to 1e-3 of
    /// the box, 1e-4 up to 6e-3, growing as its power 1.5 above; not used with --tolerance].
    #[arg(long, value_name = "L")]
    smoothing: Option<f64>,
    /// Keep every point (no outlier removal).
    #[arg(long)]
    keep_outliers: bool,
    /// For an open scan (a face, a terrain): drop the surface farther than D from every point
    /// (in the points' units), leaving an open mesh
    #[arg(long, value_name = "D")]
    trim: Option<f64>,
}

pub(crate) fn run(args: &ReconstructArgs, quiet: bool) -> Result<(), Failure> {
    let source = args.cloud.display().to_string();
    if let Some(t) = args.tolerance
        && !(t > 0.0 && t.is_finite())
    {
        return Err(Failure::new(
            USAGE,
            format!("--tolerance {t}: the tolerance must be a finite number > 0"),
        ));
    }
    if let Some(d) = args.trim
        && !(d > 0.0 && d.is_finite())
    {
        return Err(Failure::new(
            USAGE,
            format!("--trim {d}: the distance must be a finite number > 0"),
        ));
    }
    if let Some(l) = args.smoothing
        && !(l > 0.0 && l.is_finite())
    {
        return Err(Failure::new(
            USAGE,
            format!(
                "--smoothing {l}: λ must be a finite number > 0 (--tolerance T fits greedily instead)"
            ),
        ));
    }
    if let Some(n) = args.max_centres
        && n < 10
    {
        return Err(Failure::new(
            USAGE,
            format!("--max-centres {n}: at least 10"),
        ));
    }
    let start = Instant::now();
    let PointCloud {
        positions: points,
        normals,
    } = read_cloud(&args.cloud)?;
    let mut settings = ReconstructSettings {
        tolerance: args.tolerance,
        smoothing: args.smoothing,
        outlier_ratio: (!args.keep_outliers).then_some(2.5),
        ..Default::default()
    };
    if let Some(n) = args.max_centres {
        settings = settings.with_max_centres(n);
    }
    let resolution = args
        .resolution
        .unwrap_or_else(|| rbf_convert::mesh_resolution(&points));
    let bar = spinner(
        quiet,
        format!(
            "{}: reconstructing, polygonizing at {resolution}",
            points.len()
        ),
    );
    // Bubbles that no scanned point is near are not part of the scanned surface.
    let result = scan_surface(&points, normals.as_deref(), &settings, Some(resolution));
    bar.finish_and_clear();
    let ScanSurface {
        model,
        report,
        mesh,
        dropped: bubbles,
    } = result.map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
    let mesh = match args.trim {
        Some(d) => rbf_convert::trimmed(&mesh, &points, d).map_err(|e| {
            Failure::new(
                BAD_INPUT,
                format!("{source}: --trim {d} leaves no surface ({e}): the points are farther apart than that"),
            )
        })?,
        None => mesh,
    };
    write_mesh(&args.output, &mesh).map_err(|e| Failure::mesh(&e))?;
    if let Some(path) = &args.model {
        write_atomically(path, model.to_json().as_bytes())?;
    }
    if !quiet {
        let r = mesh.check();
        let beyond = format!(
            " ({} point(s) beyond the tolerance; a lower --smoothing follows the points more closely)",
            report.beyond_tolerance
        );
        eprintln!(
            "{} points read, {}{} outliers dropped{}, normals {}{} ({} flipped, {} reversed by winding numbers, {} by fits, {} by lines of sight{}, {} at odds with their neighbours left out, {} piece(s)); noise {:.1e}{}, tolerance {:.1e} of the box; {} centres{}{}, largest miss {:.1e}{}, {} outside constraints added; {} triangles at {}{}, {}; {:.2} s; wrote {}",
            report.points,
            if report.duplicates > 0 {
                format!("{} repeated and ", report.duplicates)
            } else {
                String::new()
            },
            report.outliers,
            if report.working < report.points - report.duplicates - report.outliers {
                format!(", a random {} of them worked on", report.working)
            } else {
                String::new()
            },
            match (report.normals_estimated, report.normals_filled) {
                (true, _) => "estimated".to_string(),
                (false, 0) => "given".to_string(),
                (false, n) => format!("given, {n} of zero length estimated"),
            },
            if report.neighbours > settings.neighbours {
                format!(
                    ", from {} neighbours each (the points lie in lines, slices or profiles, farther apart than fewer reach)",
                    report.neighbours
                )
            } else {
                String::new()
            },
            report.flipped,
            report.reversed_by_winding,
            report.refuted,
            report.reversed_by_sight,
            if report.looked_again {
                " (a second attempt with lines of sight: the first fit strayed out, or its mesh was open)"
            } else {
                ""
            },
            report.disagreeing,
            report.pieces,
            report.noise,
            if report.smoothed {
                " (points smoothed)"
            } else {
                ""
            },
            report.tolerance,
            report.centres,
            match report.added_where_sheets_close {
                0 => String::new(),
                n => format!(" ({n} of them added where two sheets run close)"),
            },
            if report.lambda > 0.0 {
                format!(" in a smoothing fit (λ {:.1e})", report.lambda)
            } else {
                String::new()
            },
            report.largest_miss,
            match (report.within_tolerance, report.lambda > 0.0) {
                (true, _) => "",
                (false, false) => {
                    " (above the tolerance: the centre budget ran out; raise --max-centres)"
                }
                (false, true) => &beyond,
            },
            report.outside_added,
            r.triangles,
            resolution,
            match bubbles {
                0 => String::new(),
                n => format!(
                    " ({n} piece(s) the scan cannot show dropped: bubbles away from every point, crumbs, closed cavities)"
                ),
            },
            crate::common::surface_topology(&r, "open"),
            start.elapsed().as_secs_f64(),
            args.output.display()
        );
    }
    Ok(())
}

/// Points and their normals (when the file has them).
fn read_cloud(path: &Path) -> Result<PointCloud, Failure> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("xyz" | "txt") => {
            let text = read_text(path)?;
            let columns = text
                .lines()
                .map(str::trim)
                .find(|l| !l.is_empty() && !l.starts_with('#'))
                .map_or(3, |l| {
                    l.split(|c: char| c.is_whitespace() || c == ',')
                        .filter(|w| !w.is_empty())
                        .count()
                });
            let bad = |e: rbf_core::ParseError| {
                Failure::new(BAD_INPUT, format!("{}: {e}", path.display()))
            };
            if columns == 6 {
                let rows = rbf_core::parse_points::<6>(&text).map_err(bad)?;
                Ok(PointCloud {
                    positions: rows.iter().map(|r| [r[0], r[1], r[2]]).collect(),
                    normals: Some(rows.iter().map(|r| [r[3], r[4], r[5]]).collect()),
                })
            } else {
                Ok(PointCloud {
                    positions: rbf_core::parse_points::<3>(&text).map_err(bad)?,
                    normals: None,
                })
            }
        }
        _ => rbf_mesh::read_point_cloud(path).map_err(|e| Failure::mesh(&e)),
    }
}
