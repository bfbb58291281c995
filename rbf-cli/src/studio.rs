//! `rbf studio`: serves the studio page (`web/`, built by `web/build.sh`) on 127.0.0.1, and a
//! model to open with it.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use clap::Args;

use crate::common::read_model_3d;
use crate::failure::{BAD_INPUT, Failure, USAGE};

pub(crate) const HELP: &str = "\
Sculpt in the browser (Turk & O'Brien 2002, §5): click the surface to add a constraint there,
drag handles and watch the surface follow, pull normal handles, undo and redo, save the model
and export the mesh. The page is served on 127.0.0.1 only; open the URL it prints.

Build the page once (installs the wasm32 target and wasm-bindgen-cli when missing):
  web/build.sh

Examples:
  rbf studio
  rbf studio torus.json --port 8190";

#[derive(Args, Debug)]
pub(crate) struct StudioArgs {
    /// A model file to open (from `rbf fit`, `rbf convert` or a saved session); the paper's
    /// starting blob by default.
    model: Option<PathBuf>,
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 8190)]
    port: u16,
    /// The page's folder (`web/` of the source tree by default).
    #[arg(long, value_name = "DIR")]
    web: Option<PathBuf>,
}

/// What the server hands out: the page's folder and the model to open, if any.
struct Site {
    root: PathBuf,
    model: Option<Vec<u8>>,
    /// The port served, for checking the `Host` header.
    port: u16,
}

/// Bytes a request's line and headers may take.
const MAX_REQUEST: u64 = 16 << 10;

pub(crate) fn run(args: &StudioArgs, quiet: bool) -> Result<(), Failure> {
    let root = args
        .web
        .clone()
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../web"));
    if !root.join("pkg/rbf_web.js").is_file() {
        return Err(Failure::new(
            USAGE,
            format!(
                "the studio page is not built ({} has no pkg/rbf_web.js): run web/build.sh first",
                root.display()
            ),
        ));
    }
    let model = match &args.model {
        Some(path) => {
            // Read it now, so that a bad file is refused here and not in the page.
            read_model_3d(path, "studio")?;
            Some(
                std::fs::read(path)
                    .map_err(|e| Failure::new(BAD_INPUT, format!("{}: {e}", path.display())))?,
            )
        }
        None => None,
    };
    let listener = TcpListener::bind(("127.0.0.1", args.port)).map_err(|e| {
        Failure::new(
            BAD_INPUT,
            format!(
                "127.0.0.1:{}: {e}; choose another with --port N (0 takes any free port)",
                args.port
            ),
        )
    })?;
    let port = listener.local_addr().map(|a| a.port()).unwrap_or(args.port);
    println!("rbf studio at http://127.0.0.1:{port}/ (Ctrl+C stops it)");
    if !quiet && let Some(path) = &args.model {
        eprintln!("opening {}", path.display());
    }
    let _ = std::io::stdout().flush();
    let site = Arc::new(Site { root, model, port });
    for stream in listener.incoming().flatten() {
        let site = Arc::clone(&site);
        std::thread::spawn(move || {
            let _ = serve(stream, &site);
        });
    }
    Ok(())
}

/// Answers one request: GET of a file under the page's folder, `studio.json` (what to open)
/// and `model.json` (the model given on the command line).
fn serve(stream: TcpStream, site: &Site) -> std::io::Result<()> {
    // A client that stalls or sends without end is dropped.
    stream.set_read_timeout(Some(std::time::Duration::from_secs(10)))?;
    let mut reader = BufReader::new(Read::take(stream.try_clone()?, MAX_REQUEST));
    let mut request = String::new();
    reader.read_line(&mut request)?;
    // The headers: only `Host` matters, which must name this server (a page elsewhere that
    // points a name of its own at 127.0.0.1 gets nothing).
    let mut host_ok = false;
    let mut line = String::new();
    while reader.read_line(&mut line)? > 2 {
        if let Some((name, value)) = line.split_once(':')
            && name.trim().eq_ignore_ascii_case("host")
        {
            let value = value.trim();
            host_ok = [
                format!("127.0.0.1:{}", site.port),
                format!("localhost:{}", site.port),
            ]
            .iter()
            .any(|h| h == value);
        }
        line.clear();
    }
    let mut words = request.split_whitespace();
    let (method, target) = (words.next().unwrap_or(""), words.next().unwrap_or("/"));
    let path = target.split(['?', '#']).next().unwrap_or("/");
    let reply = |status: &str, kind: &str, body: &[u8]| -> std::io::Result<()> {
        let mut out = &stream;
        write!(
            out,
            "HTTP/1.1 {status}\r\nContent-Type: {kind}\r\nContent-Length: {}\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n",
            body.len()
        )?;
        out.write_all(body)
    };
    if method != "GET" {
        return reply("405 Method Not Allowed", "text/plain", b"GET only\n");
    }
    if !host_ok {
        return reply("403 Forbidden", "text/plain", b"ask for 127.0.0.1\n");
    }
    match path {
        "/studio.json" => {
            let config: &[u8] = if site.model.is_some() {
                br#"{"model": "model.json"}"#
            } else {
                b"{}"
            };
            reply("200 OK", "application/json", config)
        }
        "/model.json" => match &site.model {
            Some(bytes) => reply("200 OK", "application/json", bytes),
            None => reply("404 Not Found", "text/plain", b"no model was given\n"),
        },
        _ => {
            let relative = match path.strip_prefix('/').unwrap_or(path) {
                "" => "index.html",
                name => name,
            };
            // Only plain names below the page's folder: no `..`, no root, no drive, no
            // backslash; checked before anything is opened.
            let safe = !relative.contains(['\\', ':'])
                && !relative.split('/').any(str::is_empty)
                && Path::new(relative)
                    .components()
                    .all(|c| matches!(c, Component::Normal(_)));
            let file = site.root.join(relative);
            match safe.then(|| std::fs::read(&file)) {
                Some(Ok(body)) => reply("200 OK", content_type(relative), &body),
                _ => reply("404 Not Found", "text/plain", b"not found\n"),
            }
        }
    }
}

fn content_type(path: &str) -> &'static str {
    match path.rsplit('.').next() {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript",
        Some("wasm") => "application/wasm",
        Some("css") => "text/css",
        Some("json") => "application/json",
        Some("png") => "image/png",
        _ => "application/octet-stream",
    }
}
