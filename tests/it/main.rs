//! The integration tests: one crate, so the library and its dependencies link once, the shared
//! fixtures compile once and one process probes the adapter once. The modules say what a test
//! needs, and the test command filters by them:
//!
//! * `cpu`: loaders, shaders, property tests — no adapter;
//! * `gpu`: rendering through the library on the headless adapter;
//! * `cli`: the `ssdo` binary (and the viewer) as a user runs them;
//! * `backends`: the same frames on Vulkan and GL side by side (both adapters in one process).
//!
//! `scripts/test.sh` runs everything on Vulkan, then `gpu::` and `cli::` again on GL. Two tests
//! keep a process of their own (`tests/memory.rs`: a counting global allocator;
//! `tests/resources.rs`: the process's resident memory from `/proc/self`): in this crate they
//! would count what other tests running beside them hold.

mod common;

mod backends;

mod cpu {
    mod bounce_places;
    mod fuzz_entries;
    mod fuzz_loaders;
    mod help_defaults;
    mod hostile_files;
    mod imports;
    mod presets;
    mod scene_loading;
    mod shaders;
    mod special_files;
    mod surface_maps_loading;
}

mod gpu {
    mod display;
    mod far_side;
    mod march;
    mod occlusion;
    mod reference;
    mod render;
    mod sky_bounce;
    mod stability;
    mod surface_maps;
    mod temporal;
    mod thickness;
    mod tune;
    mod view_truth;
    mod winding;
}

mod cli {
    mod bad_input;
    mod binary;
    mod formats;
    mod hardening;
    mod viewer;
}
