//! The preset reader on arbitrary bytes; the body is `tests/it/cpu/fuzz_entries.rs`, which the
//! tests compile and run on the seeds and every input a fuzzer failed on.
#![no_main]

#[path = "../../tests/it/cpu/fuzz_entries.rs"]
mod entries;

libfuzzer_sys::fuzz_target!(|data: &[u8]| entries::preset(data));
