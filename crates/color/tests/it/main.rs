//! Integration tests of gonio-color: colorimetry against colour-science. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod colorchecker;
