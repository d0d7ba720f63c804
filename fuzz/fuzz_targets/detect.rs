#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = gonio_surface::io::read_bytes(std::path::Path::new("fuzz-input"), data);
});
