//! Every input in the corpora (seeds, and inputs that once crashed) through every target, on
//! stable Rust: a regression test for what the fuzzers found.

use std::path::Path;

fn replay(target: &str, run: fn(&[u8])) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus").join(target);
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
        let data = std::fs::read(entry.path()).unwrap_or_default();
        run(&data);
        count += 1;
    }
    count
}

#[test]
fn every_corpus_replays_without_a_panic() {
    let targets: [(&str, fn(&[u8])); 12] = [
        ("obj", rbf_fuzz::obj),
        ("ply", rbf_fuzz::ply),
        ("stl", rbf_fuzz::stl),
        ("point_cloud", rbf_fuzz::point_cloud),
        ("constraints_text", rbf_fuzz::constraints_text),
        ("constraints_json", rbf_fuzz::constraints_json),
        ("model_json", rbf_fuzz::model_json),
        ("fit", rbf_fuzz::fit),
        ("evaluate", rbf_fuzz::evaluate),
        ("polygonize", rbf_fuzz::polygonize),
        ("voxelize", rbf_fuzz::voxelize),
        ("far_field", rbf_fuzz::far_field),
    ];
    for (name, run) in targets {
        assert!(replay(name, run) > 0, "the {name} corpus is empty");
    }
}
