//! Every GL test in one binary (one link instead of fourteen): real Mesa GL through EGL, no display.
//! The window tests, which need Xvfb, are the other binary (`tests/window_panel.rs`).

mod ao_resolution;
mod bench;
mod bench_html;
mod bench_model;
mod bench_skips;
mod bench_split;
mod blur_stripes;
mod classroom;
mod cli;
mod closed_pipe;
#[path = "../common/mod.rs"]
mod common;
mod composite_modes;
mod depth_layers;
mod engine_options;
mod error_map;
mod gl_basics;
mod gltf_files;
mod grade;
mod grade_class;
mod grade_class_zip;
mod grade_mutation;
mod guard_band;
mod i18n;
mod inputs;
mod inputs_limits;
mod inputs_misread;
mod lessons_ja;
mod methods;
mod numerics;
mod obj_corpus;
mod obj_files;
mod reference_analytic;
mod reference_backface;
mod reference_screen;
mod reference_slabs;
mod rtao;
mod sao_pipeline;
mod shader_interface;
mod shader_memory;
mod surface_normals;
mod tune;
mod vbao;
mod vbao_convergence;
mod window_truth;
