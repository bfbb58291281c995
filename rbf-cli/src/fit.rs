//! `rbf fit`: constraints in, model file out.

use std::path::PathBuf;
use std::time::Instant;

use crate::fit_progress::FitMessages;
use clap::{Args, ValueEnum};
use rbf_core::{
    AnyModel, Constraint, ConstraintFile, FitSettings, Model, NormalOffset, SolveMethod,
};
use rbf_solve::{FitOptions, GreedySettings, IterativeOptions, Method, SolveOptions, Strategy};

use crate::KernelArg;
use crate::common::{read_text, spinner, write_atomically};
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Input formats:
  Text, one constraint per line (# starts a comment; spaces, tabs or commas separate):
    3D:  x y z value       boundary if value = 0, interior if > 0, exterior if < 0
         x y z nx ny nz    an oriented point: boundary + normal constraint
    2D (--dim 2):  x y value   or   x y nx ny
  JSON: {\"dim\": 3, \"lambda\": 0, \"constraints\": [
           {\"kind\": \"boundary\", \"position\": [0, 0, 1]},
           {\"kind\": \"interior\", \"position\": [0, 0, 0], \"value\": 1},
           {\"kind\": \"exterior\", \"position\": [3, 3, 3], \"value\": -1},
           {\"kind\": \"normal\", \"position\": [1, 0, 0], \"normal\": [1, 0, 0]}]}
  (see the README for every field).
  Point clouds, 3D, by extension:
    .ply   vertices with x y z nx ny nz (ASCII or binary; faces ignored): oriented points
    .npy   N x 6 (x y z nx ny nz) oriented points, or N x 4 (x y z value); float64 or float32
  A cloud without normals is refused here: `rbf reconstruct` estimates and orients them.

Examples:
  rbf fit points.txt -o model.json
  rbf fit curve.txt --dim 2 -o curve.json
  rbf fit scan.json --lambda 1e-4 -o smooth.json
  rbf fit bunny.json --lambda 1e-3 -o smoother.json   (re-solve a model's constraints)
  rbf fit scan.ply -o scan.json   (35 000 oriented points, 70 000 rows: above 5000 rows the
      iterative solver takes every point, in memory and time that grow with the rows)
  rbf fit scan.ply --method greedy --tolerance 1e-4 -o small.json   (a subset of centres,
      grown until the surface meets every point within 1e-4 of the box: a smaller model)

Methods (--method):
  auto     dense below 5000 rows, iterative above
  dense    a factorization of the whole system (--solver): O(K²) memory, O(K³) time, residual
           near rounding, with a condition estimate
  fast     flexible GMRES preconditioned by overlapping subdomains and a coarse level (Beatson,
           Light & Billings 2000): O(K) memory; stops when max|f(cᵢ) − hᵢ| ≤ max|hᵢ| ×
           --max-residual (1e-5 unless given: at every row by direct sums, or GMRES's own residual
           certified at 2000 rows), or fails (--allow-unconverged keeps the model with a warning);
           from 400 000 rows its products go through a far field whose claimed residual is
           checked by direct sums at 2000 sampled rows; from 175 000 rows, once the residual is
           small, products go through cheaper far fields (their error allowed to grow as the
           residual falls; checks then take exact products; --exact turns both off)
  greedy   a subset of the constraints (--tolerance, --max-centres)";

#[derive(Args, Debug)]
pub(crate) struct FitArgs {
    /// Constraint file (JSON or text), a point cloud (.ply with normals, .npy), or a model file
    /// whose constraints are solved again (with its settings, unless overridden); `-` reads stdin.
    input: PathBuf,
    /// Model file to write (JSON).
    #[arg(short, long, value_name = "MODEL.json")]
    output: PathBuf,
    /// Regularization λ ≥ 0 on the diagonal (subtracted for the linear kernel r, as scipy's
    /// smoothing): 0 interpolates exactly, larger is smoother.
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    lambda: Option<f64>,
    /// Radial kernel [default: thin-plate in 2D, cubic in 3D].
    #[arg(long, value_enum)]
    kernel: Option<KernelArg>,
    /// Dimension of a text input [default: 3, or the JSON file's].
    #[arg(long, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: Option<u8>,
    /// Distance from a normal constraint to its inside point [default: 0.01 × the longest side
    /// of the bounding box].
    #[arg(long, value_name = "D", allow_hyphen_values = true)]
    offset: Option<f64>,
    /// Two points closer than this fraction of the bounding box's longest side are an error
    /// (coincident constraints make the system singular).
    #[arg(long, value_name = "F", default_value_t = 1e-9)]
    min_separation: f64,
    /// Largest accepted residual max|f(cᵢ) − hᵢ| / max|hᵢ|; a fit that misses it fails
    /// [default: 1e-6 by the dense method, 1e-5 by the iterative one (17 times tighter than
    /// tuned ferreus-rbf reaches on its own benchmark); without it, an iterative solve that
    /// stalls at the rounding floor of its products is accepted with a note].
    #[arg(long, value_name = "R")]
    max_residual: Option<f64>,
    /// How the system is solved (see below).
    #[arg(long, value_enum, default_value_t = MethodArg::Auto)]
    method: MethodArg,
    /// With the dense method: the factorization.
    #[arg(long, value_enum, default_value_t = SolverArg::Auto)]
    solver: SolverArg,
    /// The same as --method greedy.
    #[arg(long, conflicts_with_all = ["solver", "method"])]
    greedy: bool,
    /// With the fast method: most iterations.
    #[arg(long, value_name = "N", default_value_t = 300)]
    max_iterations: usize,
    /// With the fast method: write the model of a solve that stopped short of its tolerance (a
    /// warning says how far it got) instead of failing; it must still meet --max-residual.
    #[arg(long)]
    allow_unconverged: bool,
    /// With the fast method: take every product by direct sums, however many rows (by default
    /// from 400 000 rows they go through a far field, and from 175 000 rows the products of late
    /// iterations, once the residual is small, through cheaper, less accurate ones).
    #[arg(long)]
    exact: bool,
    /// With --method greedy: the largest miss allowed, |f − h| / |∇f| at every constraint, as a
    /// fraction of the bounding box's longest side [default: 1e-4].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    tolerance: Option<f64>,
    /// With --method greedy: the most constraints the fit may use (if it needs more, the best fit
    /// within the budget is written, with a warning) [default: 5000].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    max_centres: Option<u64>,
}

/// Solvers by their command-line names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum MethodArg {
    /// Dense below 5000 rows, fast above.
    Auto,
    /// A factorization of the whole system.
    Dense,
    /// Preconditioned GMRES: memory and time that grow with the rows.
    Fast,
    /// A subset of the constraints, grown until every one is met within --tolerance.
    Greedy,
}

/// Factorizations by their command-line names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum SolverArg {
    /// Cholesky of the projected system; LBLᵀ, then LU, if needed.
    Auto,
    /// Cholesky of the projected system only.
    Cholesky,
    /// Bunch–Kaufman LBLᵀ of the projected system.
    Lblt,
    /// LU of the whole system.
    Lu,
}

pub(crate) fn run(args: &FitArgs, quiet: bool, verbose: bool) -> Result<(), Failure> {
    let source = args.input.display().to_string();
    refuse_cloud_too_large(args, &source)?;
    let cloud = read_cloud(&args.input, &source)?;
    let text = match cloud {
        Some(_) => String::new(),
        None => read_text(&args.input)?,
    };
    let mut settings = FitSettings::default();
    if let Some(k) = args.kernel {
        settings.kernel = Some(k.into());
    }
    let json = text.trim_start().starts_with('{');
    let model = json && text.contains("\"format\"");
    let (dim, source_kind) = if let Some(constraints) = cloud {
        if args.dim == Some(2) {
            return Err(Failure::new(
                USAGE,
                format!("--dim 2 contradicts {source}, a point cloud in 3D"),
            ));
        }
        (3, Source::Cloud(constraints))
    } else if model {
        // A model file: re-solve its constraints, with its settings unless overridden.
        let model = AnyModel::from_json(&text).map_err(|e| Failure::file(&source, &e))?;
        let (dim, model_settings) = match &model {
            AnyModel::Two(m) => (2, m.settings),
            AnyModel::Three(m) => (3, m.settings),
        };
        if let Some(d) = args.dim
            && usize::from(d) != dim
        {
            return Err(Failure::new(
                USAGE,
                format!("--dim {d} contradicts {source}, which is {dim}D"),
            ));
        }
        settings = FitSettings {
            kernel: settings.kernel.or(model_settings.kernel),
            ..model_settings
        };
        (dim, Source::Model(model))
    } else if json {
        let file = ConstraintFile::from_json(&text).map_err(|e| Failure::file(&source, &e))?;
        let dim = file.dimension().map_err(|e| Failure::file(&source, &e))?;
        if let Some(d) = args.dim
            && usize::from(d) != dim
        {
            return Err(Failure::new(
                USAGE,
                format!("--dim {d} contradicts {source}, which is {dim}D"),
            ));
        }
        settings = file.settings(settings);
        (dim, Source::Constraints(file))
    } else {
        (usize::from(args.dim.unwrap_or(3)), Source::Text)
    };
    if let Some(l) = args.lambda {
        settings.lambda = l;
    }
    settings.min_separation = args.min_separation;
    if let Some(r) = args.max_residual {
        if !FitSettings::max_residual_is_valid(r) {
            return Err(Failure::new(
                USAGE,
                format!(
                    "--max-residual must be a finite fraction of max|h| ≥ 1e-15 (double precision cannot certify less), not {r}"
                ),
            ));
        }
        settings.max_residual = r;
    }
    if let Some(o) = args.offset {
        settings.normal_offset = NormalOffset::Absolute(o);
    }
    let options = SolveOptions {
        strategy: match args.solver {
            SolverArg::Auto => Strategy::Auto,
            SolverArg::Cholesky => Strategy::Cholesky,
            SolverArg::Lblt => Strategy::Lblt,
            SolverArg::Lu => Strategy::Lu,
        },
        ..Default::default()
    };
    let method = if args.greedy {
        MethodArg::Greedy
    } else {
        args.method
    };
    if method != MethodArg::Greedy && (args.tolerance.is_some() || args.max_centres.is_some()) {
        return Err(Failure::new(
            USAGE,
            "--tolerance and --max-centres belong to --method greedy (the other methods meet every constraint; see --max-residual)",
        ));
    }
    if method != MethodArg::Dense && method != MethodArg::Auto && args.solver != SolverArg::Auto {
        return Err(Failure::new(
            USAGE,
            "--solver chooses the dense method's factorization: use it with --method dense",
        ));
    }
    let tolerance = args.tolerance.unwrap_or(1e-4);
    let job = Job {
        source: &source,
        text: &text,
        input: &source_kind,
        settings,
        options,
        quiet,
        verbose,
        output: &args.output,
        method,
        iterative: IterativeOptions {
            max_iterations: args.max_iterations,
            allow_unconverged: args.allow_unconverged,
            far_field_rows: if args.exact {
                usize::MAX
            } else {
                IterativeOptions::default().far_field_rows
            },
            relaxed_rows: if args.exact {
                usize::MAX
            } else {
                IterativeOptions::default().relaxed_rows
            },
            ..Default::default()
        }
        .with_limit_given(args.max_residual.is_some()),
        greedy: GreedySettings {
            tolerance,
            max_constraints: usize::try_from(args.max_centres.unwrap_or(5000))
                .unwrap_or(usize::MAX),
            ..Default::default()
        },
    };
    if !(tolerance >= 0.0 && tolerance.is_finite()) {
        return Err(Failure::new(
            USAGE,
            format!("--tolerance must be a finite number ≥ 0, not {}", tolerance),
        ));
    }
    match dim {
        2 => job.run::<2>(),
        _ => job.run::<3>(),
    }
}

/// Refuses a point cloud whose header declares more points than memory can take, for the
/// method that would fit them, before the file is read.
fn refuse_cloud_too_large(args: &FitArgs, source: &str) -> Result<(), Failure> {
    let Some((points, columns)) =
        rbf_mesh::declared_cloud_size(&args.input).map_err(|e| Failure::mesh(&e))?
    else {
        return Ok(());
    };
    let points = usize::try_from(points).unwrap_or(usize::MAX);
    // An oriented point gives two rows, a valued one (.npy N × 4) one.
    let rows = points.saturating_mul(if columns == 4 { 1 } else { 2 });
    let greedy = args.greedy || args.method == MethodArg::Greedy;
    let checked = if greedy {
        // The greedy fit keeps every constraint (about 200 bytes each) and its budget's system.
        let budget = args.max_centres.unwrap_or(5000) as usize;
        rbf_solve::check_fits(budget.min(points).saturating_mul(2), 1).and_then(|()| {
            let bytes = (points as u64).saturating_mul(200);
            match rbf_solve::memory_budget() {
                Some(available) if bytes > available => Err(rbf_core::FitError::TooLarge {
                    rows,
                    bytes,
                    available: Some(available),
                }),
                _ => Ok(()),
            }
        })
    } else if args.method == MethodArg::Dense || rows <= rbf_solve::DENSE_LIMIT {
        rbf_solve::check_fits(rows.saturating_add(4), 1)
    } else {
        rbf_solve::check_iterative_fits(rows, 3, &IterativeOptions::default())
    };
    checked.map_err(|e| Failure::fit(source, &e))
}

/// What kind of file `rbf fit` reads its constraints from.
enum Source {
    /// A text constraint file, one constraint per line, parsed when fitted.
    Text,
    /// A JSON constraint file, whose settings (kernel, λ, normal offset) were already applied.
    Constraints(ConstraintFile),
    /// A model file, whose constraints are solved again.
    Model(AnyModel),
    /// A point cloud (PLY, `.npy`), read into constraints.
    Cloud(Vec<Constraint<3>>),
}

/// Constraints from a point cloud file (`.ply` with normals, `.npy` of N × 4 values or N × 6
/// oriented points), or `None` for other files. A cloud without normals is an error that says
/// what is missing.
fn read_cloud(path: &std::path::Path, source: &str) -> Result<Option<Vec<Constraint<3>>>, Failure> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let no_normals = || {
        Failure::new(
            BAD_INPUT,
            format!(
                "{source} has points but no normals: a surface through points needs each point's outward normal (PLY vertex properties nx ny nz, or .npy columns 4-6); `rbf reconstruct` estimates and orients them and fits the surface, or give values: x y z value"
            ),
        )
    };
    match extension.as_deref() {
        Some("ply") => {
            let cloud = rbf_mesh::read_point_cloud(path).map_err(|e| Failure::mesh(&e))?;
            let normals = cloud.normals.ok_or_else(no_normals)?;
            Ok(Some(
                cloud
                    .positions
                    .into_iter()
                    .zip(normals)
                    .map(|(p, n)| Constraint::normal(p, n))
                    .collect(),
            ))
        }
        Some("npy") => {
            let bytes = std::fs::read(path)
                .map_err(|e| Failure::new(BAD_INPUT, format!("{source}: {e}")))?;
            let m = rbf_mesh::read_npy_matrix(path, &bytes).map_err(|e| Failure::mesh(&e))?;
            let at = |i: usize, d: usize| m.data[i * m.cols + d];
            let point = |i: usize| [at(i, 0), at(i, 1), at(i, 2)];
            let constraints = match m.cols {
                4 => (0..m.rows)
                    .map(|i| match at(i, 3) {
                        v if v > 0.0 => Constraint::interior(point(i), v),
                        v if v < 0.0 => Constraint::exterior(point(i), v),
                        // 0, or NaN: the constraint checks name a NaN by its index.
                        v => Constraint::boundary(point(i)).with_value(v),
                    })
                    .collect(),
                6 => (0..m.rows)
                    .map(|i| Constraint::normal(point(i), [at(i, 3), at(i, 4), at(i, 5)]))
                    .collect(),
                3 => return Err(no_normals()),
                cols => {
                    return Err(Failure::new(
                        BAD_INPUT,
                        format!(
                            "{source}: an array of {cols} columns: give N × 4 (x y z value) or N × 6 (x y z nx ny nz)"
                        ),
                    ));
                }
            };
            Ok(Some(constraints))
        }
        _ => Ok(None),
    }
}

/// A constraint of dimension A as one of dimension D (the caller checked that A is D).
fn cast<const A: usize, const D: usize>(c: &Constraint<A>) -> Constraint<D> {
    Constraint {
        kind: c.kind,
        position: core::array::from_fn(|d| c.position[d]),
        value: c.value,
        normal: core::array::from_fn(|d| c.normal[d]),
        offset: c.offset,
        smoothing: c.smoothing,
    }
}

/// A model's constraints in dimension D (the caller picked D from the model).
fn model_constraints<const D: usize>(model: &AnyModel) -> Vec<Constraint<D>> {
    match model {
        AnyModel::Two(m) => m.constraints.iter().map(cast).collect(),
        AnyModel::Three(m) => m.constraints.iter().map(cast).collect(),
    }
}

struct Job<'a> {
    source: &'a str,
    text: &'a str,
    input: &'a Source,
    settings: FitSettings,
    options: SolveOptions,
    quiet: bool,
    verbose: bool,
    output: &'a std::path::Path,
    method: MethodArg,
    iterative: IterativeOptions,
    greedy: GreedySettings,
}

impl Job<'_> {
    fn run<const D: usize>(&self) -> Result<(), Failure> {
        let constraints: Vec<Constraint<D>> = match self.input {
            Source::Constraints(f) => f
                .constraints()
                .map_err(|e| Failure::file(self.source, &e))?,
            Source::Model(m) => model_constraints(m),
            Source::Cloud(cs) => cs.iter().map(cast).collect(),
            Source::Text => rbf_core::parse_constraints(self.text)
                .map_err(|e| Failure::new(BAD_INPUT, format!("{}: {e}", self.source)))?,
        };
        if self.method == MethodArg::Greedy {
            return self.run_greedy(constraints, &self.greedy);
        }
        let start = Instant::now();
        let rows: usize = constraints.iter().map(Constraint::rows).sum();
        let options = FitOptions {
            method: match self.method {
                MethodArg::Dense => Method::Dense,
                MethodArg::Fast => Method::Iterative,
                _ => Method::Auto,
            },
            dense: self.options,
            iterative: self.iterative,
        };
        let tolerance = self
            .iterative
            .tolerance
            .unwrap_or(self.settings.max_residual);
        let spinner = spinner(self.quiet, format!("checking {rows} rows"));
        let mut messages = FitMessages::new(tolerance);
        let fit = rbf_solve::fit_with(&constraints, &self.settings, &options, |p| {
            spinner.set_message(messages.message(p));
        });
        spinner.finish_and_clear();
        let fit = fit.map_err(|e| Failure::fit(self.source, &e))?;
        let elapsed = start.elapsed();
        let report = fit.report;
        let model = Model {
            constraints,
            settings: self.settings,
            interpolant: fit.interpolant,
            report: Some(report),
        };
        write_atomically(self.output, model.to_json().as_bytes())?;
        // A fit above the limit: stopped where double precision stops it, or let through by
        // --allow-unconverged.
        let limit = messages.limit.unwrap_or(self.settings.max_residual);
        let far_rows = IterativeOptions::default().far_field_rows;
        if let Some(limit) = messages.limit.filter(|_| rows >= far_rows) {
            eprintln!(
                "rbf: note: fitted to {limit:.0e} of max|h|, the iterative solver's default limit, through the far field ({far_rows} rows or more); --max-residual 1e-6 asks for the dense method's limit, by direct sums where the far field cannot reach it (minutes a product at 10⁶ rows)"
            );
        }
        if let Some(floor) = messages.rounding_floor {
            eprintln!(
                "rbf: note: the iterative solve stalled at residual {:.1e}, above --max-residual {limit:.1e} but within what double precision allows for these constraints ({floor:.1e}: their weights are large and cancel); the model was written with that residual (a small --lambda gives a smoother, better conditioned fit)",
                report.residual
            );
        } else if report.method == SolveMethod::Iterative && report.residual > limit {
            eprintln!(
                "rbf: warning: the iterative solve stopped at residual {:.1e} after {} iterations, above --max-residual {limit:.1e}",
                report.residual, report.iterations
            );
        }
        if !self.quiet {
            let how = match (report.method, messages.relaxed) {
                (SolveMethod::Iterative, Some((products, of))) if self.verbose => format!(
                    "{} iterations ({products} of {of} products through a relaxed far field)",
                    report.iterations
                ),
                (SolveMethod::Iterative, _) => format!("{} iterations", report.iterations),
                _ => format!("condition ≈ {:.1e}", report.condition),
            };
            eprintln!(
                "fitted {} constraints ({} rows, {}D, {}) in {:.2} s: {:?}, residual {:.1e}, {how}; wrote {}",
                model.constraints.len(),
                report.rows,
                D,
                model.interpolant.kernel().name(),
                elapsed.as_secs_f64(),
                report.method,
                report.residual,
                self.output.display()
            );
        }
        Ok(())
    }
}

impl Job<'_> {
    /// `--greedy`: a subset of the constraints, grown until all are met.
    fn run_greedy<const D: usize>(
        &self,
        constraints: Vec<Constraint<D>>,
        greedy: &GreedySettings,
    ) -> Result<(), Failure> {
        let start = Instant::now();
        // The budget of centres must fit in memory (two rows for a normal constraint).
        rbf_solve::check_fits(
            greedy
                .max_constraints
                .min(constraints.len())
                .saturating_mul(2),
            1,
        )
        .map_err(|e| Failure::fit(self.source, &e))?;
        let spinner = spinner(
            self.quiet,
            format!("checking {} constraints", constraints.len()),
        );
        let mut number = 0;
        let result = rbf_solve::fit_greedy(&constraints, &self.settings, greedy, |round| {
            number += 1;
            let line = format!(
                "round {number:2}: {} constraints miss by up to {:.2e} of the box; fit {:.3} s, measure {:.3} s",
                round.constraints, round.max_error, round.fit_seconds, round.evaluate_seconds
            );
            if self.verbose {
                spinner.suspend(|| eprintln!("{line}"));
            }
            spinner.set_message(line);
        });
        spinner.finish_and_clear();
        let (fit, greedy_report) = result.map_err(|e| Failure::fit(self.source, &e))?;
        let elapsed = start.elapsed();
        let report = fit.report;
        let model = Model {
            constraints: greedy_report.constraints,
            settings: self.settings,
            interpolant: fit.interpolant,
            report: Some(report),
        };
        write_atomically(self.output, model.to_json().as_bytes())?;
        let last = greedy_report.rounds.last().map_or(0.0, |r| r.max_error);
        if !greedy_report.converged {
            let remedy = if model.constraints.len() < greedy.max_constraints {
                "the centres' own smoothing misses them: lower --lambda or raise --tolerance"
            } else {
                "raise --max-centres or --tolerance"
            };
            eprintln!(
                "rbf: warning: {} constraints still miss by up to {last:.2e} of the box (tolerance {:.1e}); {remedy}",
                model.constraints.len(),
                greedy.tolerance
            );
        }
        if !self.quiet {
            eprintln!(
                "fitted {} of {} constraints greedily ({} rounds; every constraint met within {last:.1e} of the box) in {:.2} s: {} rows, residual {:.1e}, condition ≈ {:.1e}; wrote {}",
                model.constraints.len(),
                constraints.len(),
                greedy_report.rounds.len(),
                elapsed.as_secs_f64(),
                report.rows,
                report.residual,
                report.condition,
                self.output.display()
            );
        }
        Ok(())
    }
}
