#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rbf_fuzz::point_cloud(data));
