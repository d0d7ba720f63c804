//! Integration tests of gonio-instrument: the virtual instruments on whole maps (the isotropy check, the ray method against Kirchhoff) and on a measured paint (the multi-angle spectrophotometer). One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod isotropy;
mod multiangle;
mod ray_vs_kirchhoff;
