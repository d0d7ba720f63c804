//! Integration tests of gonio-report: the reports as the front ends compose them through the
//! library. One test binary per crate; each module is one subject.

mod conformance;
mod demo;
