//! Fuzz targets for gonio's height-map readers (`cargo fuzz`, libFuzzer): one target per reader,
//! each feeding arbitrary bytes to that reader alone, and `detect`, which goes through format
//! detection as a user's file does. A reader must answer every input with a map or an error:
//! a panic, a hang or an allocation the input does not justify is a bug (the runs set
//! libFuzzer's `-malloc_limit_mb` for that). How to run them: `docs/formats.md`.

/// A fuzz target that reads its input as the [`gonio_surface::io::Format`] variant `$format`.
#[macro_export]
macro_rules! reader_target {
    ($format:ident) => {
        libfuzzer_sys::fuzz_target!(|data: &[u8]| {
            let _ = gonio_surface::io::read_bytes_as(
                gonio_surface::io::Format::$format,
                std::path::Path::new("fuzz-input"),
                data,
            );
        });
    };
}
