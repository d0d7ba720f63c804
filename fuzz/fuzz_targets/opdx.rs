#![no_main]
gonio_fuzz::reader_target!(Opdx);
