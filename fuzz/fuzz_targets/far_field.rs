#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rbf_fuzz::far_field(data));
