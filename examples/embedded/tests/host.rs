//! The exported constants evaluate exactly as the model file does.

use rbf_core::AnyModel;

#[test]
fn exported_model_matches_the_model_file_bit_for_bit() {
    let text = include_str!("../model.json");
    let Ok(AnyModel::Three(model)) = AnyModel::from_json(text) else {
        panic!("model.json is a 3D model");
    };
    for i in 0..200 {
        let t = i as f64 * 0.618_033_988_7;
        let p = [1.5 * t.sin(), 1.5 * (1.3 * t).cos(), 1.5 * (0.7 * t).sin()];
        assert_eq!(
            rbf_embedded_example::value(p),
            model.interpolant.value(&p),
            "at {p:?}"
        );
    }
}
