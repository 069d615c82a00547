// What the passes that filter the samples read (the upsample, the blur and the temporal pass,
// bind group 1, binding 3): mirrors `FilterParams` in src/render/uniforms.rs field for field
// (checked in tests/it/cpu/shaders.rs).

struct FilterParams {
    // the sampling radius, in view units (the filters' plane-distance tolerances scale with it)
    radius: f32,
    // The temporal pass (shaders/temporal.wgsl): the most frames a still pixel averages, the
    // most a moving one does, and the frames its history holds (0: nothing to reuse).
    accumulate: u32,
    motion_accumulate: u32,
    history_frames: u32,
}
