//! Fuzz target: scene-file parsing and OBJ/MTL → scene conversion (`vct::scene::fuzz_scene_input`).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| vct::scene::fuzz_scene_input(data));
