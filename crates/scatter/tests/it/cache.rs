//! The table cache: every input of a table (options, map, gonio's version) changes its file, and a
//! table is computed once.

use gonio_brdf::Ior;
use gonio_brdf::table::{Channels, Resolution, TableBuilder};
use gonio_scatter::ray::RayOptions;
use gonio_scatter::table::TableOptions;
use gonio_scatter::table::cache::*;

#[test]
fn every_input_changes_the_file_and_a_table_is_computed_once() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::new(dir.path().join("cache"));
    let (ray, table) = (RayOptions::default(), TableOptions::isotropic());
    let path = cache.path("map a", &ray, &table);
    assert_eq!(path, cache.path("map a", &ray, &table));
    let other_ray = RayOptions {
        ior: Ior::Dielectric(1.5),
        ..ray
    };
    let other_table = TableOptions {
        incidence_azimuths: 8,
        ..table
    };
    for other in [
        cache.path("map b", &ray, &table),
        cache.path("map a", &other_ray, &table),
        cache.path("map a", &ray, &other_table),
    ] {
        assert_ne!(path, other);
    }
    let make = || {
        let mut b = TableBuilder::new(Resolution::isotropic(4, 4, 4), Channels::Mono).unwrap();
        b.fill(|_, out| out[0] = 0.25);
        b.build()
    };
    let mut computed = 0;
    for _ in 0..2 {
        let t = cache
            .get_or_compute("map a", &ray, &table, || {
                computed += 1;
                make()
            })
            .unwrap();
        assert_eq!(t.values()[0], 0.25);
    }
    assert_eq!(computed, 1, "the second call reads the cached file");
}
