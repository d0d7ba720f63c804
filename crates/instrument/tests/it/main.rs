//! Integration tests of gonio-instrument: the virtual instruments on whole maps: the isotropy check and the ray method against Kirchhoff. One test binary per crate (one
//! link instead of one per file); each module is one subject.

mod isotropy;
mod ray_vs_kirchhoff;
