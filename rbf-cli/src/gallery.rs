//! `rbf gallery`: the figures of Turk & O'Brien (2002) that can be computed, each as a PNG with the
//! models behind it, a `gallery.json` of what each figure measured, and an `index.html`.

use std::f64::consts::FRAC_1_SQRT_2;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use rbf_core::{Constraint, FitSettings, Model, shapes};
use rbf_mesh::{PolygonizeSettings, Resolution, polygonize_grid};
use rbf_render::{Camera, Csg, Image, Object, PlotSettings, RenderSettings, plot_curve, render};
use serde_json::{Value, json};

use crate::failure::{BAD_INPUT, Failure};
use crate::io::write_atomically;

pub(crate) const HELP: &str = "\
Figures 1, 2, 3, 4, 5, 6, 7, 8, 9 and 10 of Turk & O'Brien (2002) and Figure 3 of Yngve & Turk
(2002), recomputed: each a PNG (two
panels side by side where the paper has two), the model files behind it, and what it measured
in gallery.json (watertightness and genus of 3D surfaces, residuals at the constraints of 2D
curves). index.html shows them with one line of caption each.

Example:
  rbf gallery -o gallery && xdg-open gallery/index.html";

#[derive(Args, Debug)]
pub(crate) struct GalleryArgs {
    /// Directory to write.
    #[arg(short, long, default_value = "rbf-gallery")]
    output: PathBuf,
    /// Side of each panel in pixels.
    #[arg(long, default_value_t = 360)]
    size: u32,
}

struct Gallery<'a> {
    dir: &'a Path,
    size: u32,
    entries: Vec<Value>,
}

fn bad(e: impl std::fmt::Display) -> Failure {
    Failure::new(BAD_INPUT, e.to_string())
}

fn fit<const D: usize>(constraints: Vec<Constraint<D>>) -> Result<Model<D>, Failure> {
    let settings = FitSettings::default();
    let fit = rbf_solve::fit(&constraints, &settings).map_err(|e| Failure::fit("gallery", &e))?;
    Ok(Model {
        constraints,
        settings,
        interpolant: fit.interpolant,
        report: Some(fit.report),
    })
}

/// Largest |f| at the model's boundary constraints.
fn boundary_residual<const D: usize>(m: &Model<D>) -> f64 {
    m.constraints
        .iter()
        .filter(|c| c.kind == rbf_core::ConstraintKind::Boundary)
        .map(|c| m.interpolant.value(&c.position).abs())
        .fold(0.0, f64::max)
}

impl Gallery<'_> {
    fn save<const D: usize>(&self, name: &str, m: &Model<D>) -> Result<(), Failure> {
        write_atomically(
            &self.dir.join(format!("{name}.json")),
            m.to_json().as_bytes(),
        )
    }

    fn plot(&self, m: &Model<2>) -> Result<Image, Failure> {
        let settings = PlotSettings {
            width: self.size,
            height: self.size,
            ..Default::default()
        };
        plot_curve(&m.interpolant.view(), &m.constraints, &settings).map_err(bad)
    }

    fn shoot(
        &self,
        models: &[&Model<3>],
        objects: &[Object],
        look: &RenderSettings,
    ) -> Result<Image, Failure> {
        let views: Vec<_> = models.iter().map(|m| m.interpolant.view()).collect();
        let (lo, hi) = rbf_render::surface_bounds(&views, objects, look).map_err(bad)?;
        let camera = Camera::orbit(lo, hi, 30.0, 25.0, self.size, self.size);
        Ok(render(&views, objects, &camera, look).map_err(bad)?.0)
    }

    fn one(&self, m: &Model<3>) -> Result<Image, Failure> {
        let look = RenderSettings {
            shadows: true,
            ..Default::default()
        };
        self.shoot(&[m], &[Object::new(Csg::Model(0), 0)], &look)
    }

    /// Watertightness and genus of a model's surface, polygonized.
    fn topology(&self, m: &Model<3>) -> Result<Value, Failure> {
        let settings = PolygonizeSettings {
            resolution: Resolution::Cells(64),
            ..Default::default()
        };
        let (mesh, _) = polygonize_grid(&m.interpolant.view(), &settings).map_err(bad)?;
        let r = mesh.check();
        Ok(json!({"watertight": r.is_watertight(), "components": r.components, "genus": r.genus}))
    }

    fn add(
        &mut self,
        name: &str,
        caption: &str,
        image: &Image,
        facts: Value,
    ) -> Result<(), Failure> {
        write_atomically(
            &self.dir.join(format!("{name}.png")),
            &image.to_png().map_err(bad)?,
        )?;
        self.entries
            .push(json!({"figure": name, "caption": caption, "facts": facts}));
        Ok(())
    }
}

fn pair(a: &Image, b: &Image) -> Result<Image, Failure> {
    Image::side_by_side(a, b).map_err(bad)
}

/// `n` oriented points on a torus about the y axis at `centre` (radii 1 and 0.35).
fn torus(centre: [f64; 3], n: usize) -> Vec<Constraint<3>> {
    shapes::torus_points(n, 0.35)
        .into_iter()
        .map(|(p, normal)| {
            let [x, y, z] = p;
            let p = [centre[0] + x, centre[1] + z, centre[2] + y];
            Constraint::normal(p, [normal[0], normal[2], normal[1]])
        })
        .collect()
}

/// A sphere of `n` oriented points about `centre`, its poles on the y axis.
fn sphere(centre: [f64; 3], radius: f64, n: usize) -> Vec<Constraint<3>> {
    shapes::fibonacci_sphere(n)
        .into_iter()
        .map(|[x, y, z]| {
            let d = [x, z, y];
            Constraint::normal(core::array::from_fn(|k| centre[k] + radius * d[k]), d)
        })
        .collect()
}

pub(crate) fn run(args: &GalleryArgs, quiet: bool) -> Result<(), Failure> {
    let start = Instant::now();
    std::fs::create_dir_all(&args.output)
        .map_err(|e| bad(format!("{}: {e}", args.output.display())))?;
    let mut g = Gallery {
        dir: &args.output,
        size: args.size.clamp(16, 2048),
        entries: Vec::new(),
    };
    let bar = indicatif::ProgressBar::new(10);
    if quiet {
        bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} figures, last {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let say = |s: &str| {
        bar.inc(1);
        bar.set_message(s.to_string());
    };

    // Figure 1: four zero-valued and one positive constraint; then three more zero-valued.
    let mut c: Vec<Constraint<2>> = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]
        .map(Constraint::boundary)
        .to_vec();
    c.push(Constraint::interior([0.0, 0.0], 1.0));
    let left = fit(c.clone())?;
    c.extend([[1.2, 1.0], [-0.3, -1.4], [-1.3, 0.9]].map(Constraint::boundary));
    let right = fit(c)?;
    g.save("fig1-left", &left)?;
    g.save("fig1-right", &right)?;
    let facts =
        json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right))});
    let image = pair(&g.plot(&left)?, &g.plot(&right)?)?;
    g.add("fig1", "Fig. 1: a curve through four zero-valued constraints around a positive one; refined by three more.", &image, facts)?;
    say("fig1");

    // Figure 2: the tetrahedron blob; a branching object from prisms.
    let blob = fit(shapes::tetrahedron_blob())?;
    let tree = fit(shapes::branching(1))?;
    g.save("fig2-left", &blob)?;
    g.save("fig2-right", &tree)?;
    let facts = json!({"left": g.topology(&blob)?, "right": g.topology(&tree)?});
    let image = pair(&g.one(&blob)?, &g.one(&tree)?)?;
    g.add("fig2", "Fig. 2: zero-valued constraints at a tetrahedron's corners around a positive one; a branching shape from prisms.", &image, facts)?;
    say("fig2");

    // Figures 3 and 6: a polygonal surface and the implicit surface through its vertices with
    // their normals (the built-in cow stands in for the paper's fist and object).
    let mesh = rbf_mesh::read_mesh_bytes(Path::new("spot.obj"), crate::demo::SPOT).map_err(bad)?;
    let settings = rbf_convert::NormalSettings {
        max_vertices: 800,
        ..Default::default()
    };
    let (cow, _) = rbf_convert::convert_normals(&mesh, &settings).map_err(bad)?;
    g.save("fig3-fig6", &cow)?;
    let (lo, hi) = mesh.bounding_box();
    let camera = Camera::orbit(lo, hi, 215.0, 20.0, g.size, g.size);
    let image = crate::demo::mesh_and_model(&mesh, &cow, &camera, rbf_render::MeshStyle::Flat)?;
    let facts = json!({"vertices_used": cow.constraints.len(), "surface": g.topology(&cow)?});
    g.add("fig3-fig6", "Figs. 3 and 6: a polygonal surface (left) and the implicit surface through 800 of its vertices and their normals (right).", &image, facts)?;
    say("fig3-fig6");

    // Figure 4: exterior constraints around two, then more, zero-valued constraints.
    let ring: Vec<Constraint<2>> = (0..8)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 8.0;
            Constraint::exterior([2.5 * a.cos(), 2.5 * a.sin()], -1.0)
        })
        .collect();
    let mut c = ring.clone();
    c.extend([[-0.8, 0.0], [0.8, 0.0]].map(Constraint::boundary));
    let left = fit(c)?;
    let mut c = ring;
    c.extend(
        [
            [-1.0, 0.0],
            [0.0, 0.6],
            [1.0, 0.2],
            [0.4, -0.9],
            [-0.5, -0.5],
            [0.5, 1.2],
        ]
        .map(Constraint::boundary),
    );
    let right = fit(c)?;
    g.save("fig4-left", &left)?;
    g.save("fig4-right", &right)?;
    let facts = json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right)), "inside_between_the_two": left.interpolant.value(&[0.0, 0.0]) > 0.0});
    g.add("fig4", "Fig. 4: eight exterior constraints around two zero-valued constraints (an ellipse-like curve), and around six.", &pair(&g.plot(&left)?, &g.plot(&right)?)?, facts)?;
    say("fig4");

    // Figure 5: boundary and normal constraints; one normal (north-west) turned.
    let normals = |nw: [f64; 2]| -> Vec<Constraint<2>> {
        vec![
            Constraint::normal([1.0, 0.0], [1.0, 0.0]),
            Constraint::normal([0.0, 1.0], [0.0, 1.0]),
            Constraint::normal([-1.0, 0.0], [-1.0, 0.0]),
            Constraint::normal([0.0, -1.0], [0.0, -1.0]),
            Constraint::normal([-FRAC_1_SQRT_2, FRAC_1_SQRT_2], nw),
        ]
    };
    let left = fit(normals([-1.0, 1.0]))?;
    let right = fit(normals([-1.0, -0.3]))?;
    g.save("fig5-left", &left)?;
    g.save("fig5-right", &right)?;
    let facts =
        json!({"boundary_residual": boundary_residual(&left).max(boundary_residual(&right))});
    g.add("fig5", "Fig. 5: the same boundary and normal constraints, with the north-west normal turned (right).", &pair(&g.plot(&left)?, &g.plot(&right)?)?, facts)?;
    say("fig5");

    // Figure 7: the sculpting start and the sculpted torus.
    let start_session = rbf_sculpt::Session::new().map_err(bad)?;
    let mut session = rbf_sculpt::Session::new().map_err(bad)?;
    let script = rbf_sculpt::parse_script(include_str!("../../rbf-sculpt/scripts/torus.json"))
        .map_err(bad)?;
    for e in &script {
        session.apply(e).map_err(bad)?;
    }
    let (a, b) = (start_session.model(), session.model());
    g.save("fig7-left", &a)?;
    g.save("fig7-right", &b)?;
    let facts = json!({"left": g.topology(&a)?, "right": g.topology(&b)?, "edits": script.len()});
    g.add("fig7", "Fig. 7: the sculpting start (four boundary constraints in a cube of exterior ones) and a torus sculpted from it by a script of edits.", &pair(&g.one(&a)?, &g.one(&b)?)?, facts)?;
    say("fig7");

    // Figure 8: changing a normal constraint.
    let mut session = rbf_sculpt::Session::new().map_err(bad)?;
    let top = session.add_boundary([0.0, 1.3, 0.0]).map_err(bad)?;
    let before = session.model();
    let handle = session.add_normal(top).map_err(bad)?;
    session.move_normal(handle, [0.35, 1.4, 0.0]).map_err(bad)?;
    let after = session.model();
    g.save("fig8-left", &before)?;
    g.save("fig8-right", &after)?;
    let facts = json!({"left": g.topology(&before)?, "right": g.topology(&after)?});
    g.add(
        "fig8",
        "Fig. 8: a surface before and after its normal constraint at the top is pulled sideways.",
        &pair(&g.one(&before)?, &g.one(&after)?)?,
        facts,
    )?;
    say("fig8");

    // Figure 9: three tori and their soft union by constraint selection.
    let tori: Vec<Model<3>> = [[-1.4, 0.0, 0.0], [0.0, 0.0, 0.0], [1.4, 0.0, 0.0]]
        .iter()
        .map(|&c| fit(torus(c, 300)))
        .collect::<Result<_, _>>()?;
    let refs: Vec<&Model<3>> = tori.iter().collect();
    let (blend, report) = rbf_convert::blend(&refs).map_err(bad)?;
    g.save("fig9-right", &blend)?;
    let objects: Vec<Object> = (0..3).map(|i| Object::new(Csg::Model(i), i)).collect();
    let look = RenderSettings {
        shadows: true,
        ..Default::default()
    };
    let left = g.shoot(&refs, &objects, &look)?;
    let facts = json!({"blend": g.topology(&blend)?, "kept": report.kept, "total": report.total});
    g.add("fig9", "Fig. 9: three overlapping tori (left) and their soft union by constraint selection (right).", &pair(&left, &g.one(&blend)?)?, facts)?;
    say("fig9");

    // Figure 10: two surfaces with shadows and reflections; CSG intersection and subtraction.
    let a = fit(sphere([-0.6, 0.0, 0.0], 0.8, 200))?;
    let b = fit(torus([0.7, 0.0, 0.0], 300))?;
    g.save("fig10-a", &a)?;
    g.save("fig10-b", &b)?;
    let mut objects: Vec<Object> = (0..2).map(|i| Object::new(Csg::Model(i), i)).collect();
    objects.iter_mut().for_each(|o| o.reflectivity = 0.35);
    let look = RenderSettings {
        shadows: true,
        reflections: 2,
        ..Default::default()
    };
    let left = g.shoot(&[&a, &b], &objects, &look)?;
    let c = fit(sphere([0.4, 0.0, 0.0], 0.8, 200))?;
    let meet = Csg::Intersection(vec![Csg::Model(0), Csg::Model(1)]);
    let cut = Csg::Difference(Box::new(Csg::Model(0)), Box::new(Csg::Model(1)));
    let look = RenderSettings {
        shadows: true,
        ..Default::default()
    };
    let middle = g.shoot(&[&a, &c], &[Object::new(meet, 1)], &look)?;
    let right = g.shoot(&[&a, &c], &[Object::new(cut, 0)], &look)?;
    g.add("fig10", "Fig. 10: two implicit surfaces with shadows and reflections; the intersection and the difference of two spheres.", &pair(&pair(&left, &middle)?, &right)?, json!({}))?;
    say("fig10");

    // Yngve & Turk 2002, Figure 3: the 2D refinement steps on a teapot silhouette, goal in grey.
    let steps = crate::refine2d::refine(96, 6).map_err(|e| Failure::fit("teapot", &e))?;
    let shown: Vec<&crate::refine2d::Step> = [0, 1, 2, steps.len() - 1]
        .iter()
        .map(|&k| &steps[k.min(steps.len() - 1)])
        .collect();
    let mut panels = Vec::new();
    for (k, step) in shown.iter().enumerate() {
        g.save(&format!("yngve-fig3-step{}", k + 1), &step.model)?;
        let settings = PlotSettings {
            width: g.size,
            height: g.size * 2 / 3,
            bounds: Some(([-1.7, -1.2], [1.9, 1.2])),
            ..Default::default()
        };
        let mut image = plot_curve(
            &step.model.interpolant.view(),
            &step.model.constraints,
            &settings,
        )
        .map_err(bad)?;
        // The goal under the curve, in grey.
        let (w, h) = (f64::from(image.width()), f64::from(image.height()));
        for y in 0..image.height() {
            for x in 0..image.width() {
                let p = [
                    -1.7 + (f64::from(x) + 0.5) / w * 3.6,
                    1.2 - (f64::from(y) + 0.5) / h * 2.4,
                ];
                if crate::refine2d::goal(p) {
                    let c = image.get(x, y);
                    image.set(x, y, c.map(|v| v * 0.82));
                }
            }
        }
        panels.push(image);
    }
    let mut strip = panels[0].clone();
    for p in &panels[1..] {
        strip = pair(&strip, p)?;
    }
    let errors: Vec<Value> = steps.iter().map(|s| json!({"max": s.max_error, "rms": s.rms_error, "constraints": s.model.constraints.len()})).collect();
    g.add("yngve-fig3", "Yngve & Turk, Fig. 3: iterative refinement in 2D, steps 1, 2, 3 and the last; the goal in grey, constraints marked.", &strip, json!({"steps": errors}))?;
    say("yngve-fig3");

    bar.finish_and_clear();
    let summary = json!({"figures": g.entries});
    write_atomically(
        &args.output.join("gallery.json"),
        serde_json::to_string_pretty(&summary)
            .unwrap_or_default()
            .as_bytes(),
    )?;
    let mut html = String::from(
        "<!doctype html>\n<meta charset=\"utf-8\">\n<title>rbf gallery</title>\n<h1>Modelling with implicit surfaces that interpolate (Turk &amp; O'Brien 2002), recomputed</h1>\n",
    );
    for e in &g.entries {
        let _ = writeln!(
            html,
            "<figure><img src=\"{0}.png\" alt=\"{0}\"><figcaption>{1}</figcaption></figure>",
            e["figure"].as_str().unwrap_or(""),
            e["caption"].as_str().unwrap_or("")
        );
    }
    write_atomically(&args.output.join("index.html"), html.as_bytes())?;
    if !quiet {
        eprintln!(
            "wrote {} figures to {} in {:.1} s",
            g.entries.len(),
            args.output.display(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
