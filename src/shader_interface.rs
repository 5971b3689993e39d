//! The Rust ↔ GLSL interface, written once: every uniform location and texture binding the engine
//! sets, and for each program the uniforms and samplers it declares (`PROGRAMS`; each AO method's
//! occlusion shader in its row, `ao::method::interface`). A GL test
//! (`tests/gl/shader_interface.rs`) builds every program and checks its active uniforms against
//! them, so a location typo on either side fails instead of being silently skipped.

/// Uniform locations, mirroring the course's `layout(location=N)` table.
pub mod loc {
    /// standard.vert / shadow.vert: `matModel`.
    pub const MODEL: i32 = 0;
    /// standard.vert / shadow.vert: `matViewProjection`.
    pub const VIEW_PROJECTION: i32 = 1;
    /// standard.vert: `matShadow`, the light's view-projection.
    pub const SHADOW_MATRIX: i32 = 2;
    /// ao/surface_normal.vert: `matView` (world → view).
    pub const VIEW_MATRIX: i32 = 3;
    /// standard.frag: `objectColor` (rgba).
    pub const OBJECT_COLOR: i32 = 100;
    /// standard.frag, sky.frag: `lightDirection` (towards the light), world space.
    pub const LIGHT_DIRECTION: i32 = 101;
    pub const LIGHT_COLOR: i32 = 102;
    pub const AMBIENT_COLOR: i32 = 103;
    /// standard.frag: 1 = sample the shadow map, 0 = fully lit.
    pub const SHADOW_ENABLED: i32 = 104;
    /// standard.frag: AO on the ambient term only (1/0), 1/screen size, visibility power.
    pub const AO_AMBIENT_ONLY: i32 = 105;
    pub const INV_SCREEN_SIZE: i32 = 106;
    pub const AO_POWER: i32 = 107;
    /// sky.frag: inverse view-projection (a view ray per pixel).
    pub const INVERSE_VIEW_PROJECTION: i32 = 110;
    /// image_processing.frag: colour matrix; bloom strength.
    pub const COLOR_MATRIX: i32 = 120;
    pub const BLOOM_STRENGTH: i32 = 121;
    /// bloom_bright.frag: brightness threshold.
    pub const BLOOM_THRESHOLD: i32 = 130;
    /// sao_down_sampling.frag: the level read (the course's `mipLevel`, location 200).
    pub const SAO_MIP_LEVEL: i32 = 200;
    /// sao.frag: (radius², radius in texcoords at 1 m, bias, intensity / r⁶) (the course's `saoInfo`).
    pub const SAO_INFO: i32 = 200;
    /// sao.frag and ao/common.glsl: NDC → view-space factors at 1 m (the course's `ndcToView`).
    pub const NDC_TO_VIEW: i32 = 201;
    /// ao/common.glsl: (radius m, bias m, intensity, pixels per metre at 1 m).
    pub const AO_INFO: i32 = 200;
    /// ao/common.glsl: (samples or directions or slices, steps).
    pub const AO_COUNTS: i32 = 202;
    /// ao/common.glsl: the clamp on the screen-space radius (half-size pixels).
    pub const MAX_RADIUS_PIXELS: i32 = 203;
    /// ao/vbao.frag: how far (m) behind each depth sample the surface extends.
    pub const AO_THICKNESS: i32 = 204;
    /// ao/vbao.frag: 1 = read each tap's thickness from the back-face depth (`texBackDepth`).
    pub const AO_BACK_FACES: i32 = 205;
    /// ao/common.glsl: 1 = normals from the surface-normal pass (`texNormal`), 0 = rebuilt from depth.
    pub const AO_SURFACE_NORMALS: i32 = 206;
    /// ao/vbao.frag: depth layers marched per tap (2 = also `texSecondDepth`).
    pub const AO_LAYERS: i32 = 207;
    /// ao/vbao.frag: 1 = read the second layer's thickness from its back faces
    /// (`texSecondBackDepth`).
    pub const AO_LAYER_BACK_FACES: i32 = 208;
    /// ao/vbao.frag: levels of `texSlabs` the taps read (0 = each tap its own texel of `texDepth`).
    pub const AO_SLAB_LEVELS: i32 = 209;
    /// debug_view.frag: which buffer to show, and a value scale.
    pub const DEBUG_VIEW_MODE: i32 = 210;
    pub const DEBUG_VIEW_SCALE: i32 = 211;
    /// ao/blur_separable.frag, ao/blur_packed.frag: (1,0) then (0,1).
    pub const BLUR_AXIS: i32 = 210;
    /// ao/upsample_bilateral.frag, ao/composite_bilateral.frag: (near, far, 1 for reversed-Z) to
    /// linearise the main depth.
    pub const UPSAMPLE_DEPTH_PLANES: i32 = 230;
    /// ao/restore_back_depth.frag, ao/restore_normal.frag: main texels per AO texel along each
    /// axis (1 or 2).
    pub const BACK_DEPTH_BLOCK: i32 = 231;
    /// ao/second_layer.frag: how far (m) behind the first layer the second begins.
    pub const LAYER_SEPARATION: i32 = 232;
    /// ao/rtao.frag: view → world matrix; (rays, first sample, unused, sequence);
    /// nodes in the BVH.
    pub const RTAO_VIEW_TO_WORLD: i32 = 240;
    pub const RTAO_FRAME: i32 = 241;
    pub const RTAO_NODE_COUNT: i32 = 243;
    /// Res/ao/common.glsl: this frame's (rotation, step offset) in [0, 1) (ao/temporal.rs).
    pub const AO_FRAME_JITTER: i32 = 215;
    /// ao/temporal_accumulate.frag: view now → view last frame (a mat4: 250–253), view → world for
    /// normals (a mat3: 254–256), both frames' NDC → view, (length, depth tolerance, normal cosine,
    /// clamp slack), whether a history exists, the intensity's exponent the mean undoes (`rtao`), the
    /// history length from which the raw occlusion is blended instead of the blurred (`rtao`).
    pub const TEMPORAL_CURRENT_TO_PREVIOUS: i32 = 250;
    pub const TEMPORAL_VIEW_TO_WORLD: i32 = 254;
    pub const TEMPORAL_NDC_TO_VIEW: i32 = 257;
    pub const TEMPORAL_PREVIOUS_NDC_TO_VIEW: i32 = 258;
    pub const TEMPORAL_INFO: i32 = 259;
    pub const TEMPORAL_HISTORY_VALID: i32 = 260;
    pub const TEMPORAL_CURVE: i32 = 261;
    pub const TEMPORAL_BLURRED_FRAMES: i32 = 262;
    /// ao/composite_tint.frag, ao/composite_bilateral.frag: tint colour and power.
    pub const AO_TINT: i32 = 220;
    pub const AO_TINT_POWER: i32 = 221;
}

/// Texture units (`layout(binding=N)`).
pub mod binding {
    /// Every full-screen pass reads its main input here.
    pub const INPUT: u32 = 0;
    /// sao_blur.frag and ao/blur_separable.frag: linear depth beside the occlusion; image processing: bloom.
    pub const SECOND_INPUT: u32 = 1;
    /// ao/upsample_bilateral.frag, ao/composite_bilateral.frag: the main depth buffer.
    pub const THIRD_INPUT: u32 = 2;
    /// ao/common.glsl: `texNormal`, the surface normals at the AO size.
    pub const SURFACE_NORMALS: u32 = 2;
    /// standard.frag: `texShadow`.
    pub const SHADOW_MAP: u32 = 2;
    /// standard.frag: occlusion for AO on the ambient term only.
    pub const AO_AMBIENT: u32 = 3;
    /// ao/vbao.frag: `texSecondDepth`, the second depth layer at the AO size.
    pub const SECOND_LAYER: u32 = 3;
    /// ao/vbao.frag: `texSecondBackDepth`, the second layer's back faces at the AO size.
    pub const SECOND_LAYER_BACK: u32 = 4;
    /// ao/vbao.frag: `texSlabs`, the slab hierarchy (`ao::slab_hierarchy`).
    pub const SLAB_HIERARCHY: u32 = 5;
    /// ao/temporal_accumulate.frag: `texRaw`, the occlusion before the blur.
    pub const TEMPORAL_RAW: u32 = 3;
}

/// Shader storage buffer bindings (`layout(std430, binding=N)`).
pub mod storage {
    /// ao/rtao.frag: `BvhNodes` and `BvhTriangles` (layout in `scene::bvh`).
    pub const BVH_NODES: u32 = 0;
    pub const BVH_TRIANGLES: u32 = 1;
    /// ao/rtao.frag: `RtaoStatus`, the count of pixels whose rays were cut short.
    pub const RTAO_STATUS: u32 = 2;
}

/// One uniform a program declares.
#[derive(Clone, Copy, Debug)]
pub struct Uniform {
    pub name: &'static str,
    pub location: i32,
}

/// One sampler a program declares.
#[derive(Clone, Copy, Debug)]
pub struct Sampler {
    pub name: &'static str,
    pub binding: u32,
}

/// A program's files and declared interface.
#[derive(Clone, Copy, Debug)]
pub struct ProgramInterface {
    pub vert: &'static str,
    pub frag: &'static str,
    pub uniforms: &'static [Uniform],
    pub samplers: &'static [Sampler],
}

pub const fn u(name: &'static str, location: i32) -> Uniform {
    Uniform { name, location }
}
pub const fn s(name: &'static str, binding: u32) -> Sampler {
    Sampler { name, binding }
}
const fn fullscreen(
    frag: &'static str,
    uniforms: &'static [Uniform],
    samplers: &'static [Sampler],
) -> ProgramInterface {
    ProgramInterface {
        vert: "simple.vert",
        frag,
        uniforms,
        samplers,
    }
}

use binding::*;
use loc::*;

/// The uniforms of `ao/common.glsl` an engine method's shader reads.
pub const AO_METHOD_UNIFORMS: &[Uniform] = &[
    u("aoInfo", AO_INFO),
    u("ndcToView", NDC_TO_VIEW),
    u("aoCounts", AO_COUNTS),
    u("maxRadiusPixels", MAX_RADIUS_PIXELS),
    u("aoSurfaceNormals", AO_SURFACE_NORMALS),
    u("aoFrameJitter", AO_FRAME_JITTER),
];
pub const AO_METHOD_SAMPLERS: &[Sampler] = &[s("texDepth", INPUT), s("texNormal", SURFACE_NORMALS)];
/// The hemisphere kernel's samples stay within the world radius: no screen clamp.
pub const AO_UNCLAMPED_UNIFORMS: &[Uniform] = &[
    u("aoInfo", AO_INFO),
    u("ndcToView", NDC_TO_VIEW),
    u("aoCounts", AO_COUNTS),
    u("aoSurfaceNormals", AO_SURFACE_NORMALS),
    u("aoFrameJitter", AO_FRAME_JITTER),
];
/// Crytek's sphere reads no normal, and no screen clamp either.
pub const AO_SPHERE_UNIFORMS: &[Uniform] = &[
    u("aoInfo", AO_INFO),
    u("ndcToView", NDC_TO_VIEW),
    u("aoCounts", AO_COUNTS),
    u("aoFrameJitter", AO_FRAME_JITTER),
];

/// The lesson's `sao.frag` (the course's locations); also the `sao-lesson` row's.
pub const LESSON_SAO_UNIFORMS: &[Uniform] = &[u("saoInfo", SAO_INFO), u("ndcToView", NDC_TO_VIEW)];
pub const LESSON_SAO_SAMPLERS: &[Sampler] = &[s("texDepth", INPUT)];

/// Every program the engine builds but the AO methods' occlusion shaders (their rows hold theirs),
/// with what it declares; the lesson's `sao.frag` is here too, as the grader checks a student's
/// against it.
pub const PROGRAMS: &[ProgramInterface] = &[
    ProgramInterface {
        vert: "standard.vert",
        frag: "standard.frag",
        uniforms: &[
            u("matModel", MODEL),
            u("matViewProjection", VIEW_PROJECTION),
            u("matShadow", SHADOW_MATRIX),
            u("objectColor", OBJECT_COLOR),
            u("lightDirection", LIGHT_DIRECTION),
            u("lightColor", LIGHT_COLOR),
            u("ambientColor", AMBIENT_COLOR),
            u("shadowEnabled", SHADOW_ENABLED),
            u("aoAmbientOnly", AO_AMBIENT_ONLY),
            u("invScreenSize", INV_SCREEN_SIZE),
            u("aoPower", AO_POWER),
        ],
        samplers: &[s("texShadow", SHADOW_MAP), s("texAO", AO_AMBIENT)],
    },
    ProgramInterface {
        vert: "shadow.vert",
        frag: "shadow.frag",
        uniforms: &[
            u("matModel", MODEL),
            u("matViewProjection", VIEW_PROJECTION),
        ],
        samplers: &[],
    },
    ProgramInterface {
        vert: "sky.vert",
        frag: "sky.frag",
        uniforms: &[
            u("matInverseViewProjection", INVERSE_VIEW_PROJECTION),
            u("lightDirection", LIGHT_DIRECTION),
        ],
        samplers: &[],
    },
    fullscreen(
        "bloom_bright.frag",
        &[u("threshold", BLOOM_THRESHOLD)],
        &[s("texColor", INPUT)],
    ),
    fullscreen("bloom_down.frag", &[], &[s("texColor", INPUT)]),
    fullscreen("bloom_up.frag", &[], &[s("texColor", INPUT)]),
    fullscreen(
        "image_processing.frag",
        &[
            u("colorMatrix", COLOR_MATRIX),
            u("bloomStrength", BLOOM_STRENGTH),
        ],
        &[s("texColor", INPUT), s("texBloom", SECOND_INPUT)],
    ),
    fullscreen(
        "debug_view.frag",
        &[u("mode", DEBUG_VIEW_MODE), u("scale", DEBUG_VIEW_SCALE)],
        &[s("texValue", INPUT)],
    ),
    // The lesson's five.
    fullscreen("sao_restore_depth.frag", &[], &[s("texDepth", INPUT)]),
    fullscreen(
        "sao_down_sampling.frag",
        &[u("mipLevel", SAO_MIP_LEVEL)],
        &[s("texDepth", INPUT)],
    ),
    fullscreen("sao.frag", LESSON_SAO_UNIFORMS, LESSON_SAO_SAMPLERS),
    fullscreen(
        "sao_blur.frag",
        &[],
        &[s("texColor", INPUT), s("texDepth", SECOND_INPUT)],
    ),
    fullscreen("simple.frag", &[], &[s("texColor", INPUT)]),
    // The engine's AO programs.
    fullscreen(
        "ao/restore_depth_reversed.frag",
        &[],
        &[s("texDepth", INPUT)],
    ),
    fullscreen("ao/restore_depth_full.frag", &[], &[s("texDepth", INPUT)]),
    fullscreen(
        "ao/upsample_bilateral.frag",
        &[u("depthPlanes", UPSAMPLE_DEPTH_PLANES)],
        &[
            s("texOcclusion", INPUT),
            s("texDepth", SECOND_INPUT),
            s("texMainDepth", THIRD_INPUT),
        ],
    ),
    fullscreen(
        "ao/composite_bilateral.frag",
        &[
            u("tint", AO_TINT),
            u("power", AO_TINT_POWER),
            u("depthPlanes", UPSAMPLE_DEPTH_PLANES),
        ],
        &[
            s("texOcclusion", INPUT),
            s("texDepth", SECOND_INPUT),
            s("texMainDepth", THIRD_INPUT),
        ],
    ),
    fullscreen(
        "ao/restore_depth_full_reversed.frag",
        &[],
        &[s("texDepth", INPUT)],
    ),
    fullscreen(
        "ao/blur_separable.frag",
        &[u("axis", BLUR_AXIS)],
        &[s("texColor", INPUT), s("texDepth", SECOND_INPUT)],
    ),
    fullscreen(
        "ao/blur_packed.frag",
        &[u("axis", BLUR_AXIS)],
        &[s("texPacked", INPUT)],
    ),
    fullscreen(
        "ao/composite_tint.frag",
        &[u("tint", AO_TINT), u("power", AO_TINT_POWER)],
        &[s("texOcclusion", INPUT)],
    ),
    fullscreen(
        "ao/slab_hierarchy.frag",
        &[
            u("mipLevel", SAO_MIP_LEVEL),
            u("aoThickness", AO_THICKNESS),
            u("aoBackFaces", AO_BACK_FACES),
        ],
        &[
            s("texDepth", INPUT),
            s("texBackDepth", SECOND_INPUT),
            s("texSlabs", THIRD_INPUT),
        ],
    ),
    fullscreen(
        "ao/restore_back_depth.frag",
        &[
            u("depthPlanes", UPSAMPLE_DEPTH_PLANES),
            u("blockSize", BACK_DEPTH_BLOCK),
        ],
        &[s("texDepth", INPUT), s("texFrontDepth", SECOND_INPUT)],
    ),
    ProgramInterface {
        vert: "shadow.vert",
        frag: "ao/second_layer.frag",
        uniforms: &[
            u("matModel", MODEL),
            u("matViewProjection", VIEW_PROJECTION),
            u("depthPlanes", UPSAMPLE_DEPTH_PLANES),
            u("layerSeparation", LAYER_SEPARATION),
        ],
        samplers: &[s("texFrontDepth", INPUT)],
    },
    ProgramInterface {
        vert: "ao/surface_normal.vert",
        frag: "ao/surface_normal.frag",
        uniforms: &[
            u("matModel", MODEL),
            u("matViewProjection", VIEW_PROJECTION),
            u("matView", VIEW_MATRIX),
        ],
        samplers: &[],
    },
    fullscreen(
        "ao/restore_normal.frag",
        &[
            u("depthPlanes", UPSAMPLE_DEPTH_PLANES),
            u("blockSize", BACK_DEPTH_BLOCK),
        ],
        &[s("texNormal", INPUT), s("texFrontDepth", SECOND_INPUT)],
    ),
    fullscreen(
        "ao/temporal_accumulate.frag",
        &[
            u("currentToPrevious", TEMPORAL_CURRENT_TO_PREVIOUS),
            u("viewToWorld", TEMPORAL_VIEW_TO_WORLD),
            u("ndcToView", TEMPORAL_NDC_TO_VIEW),
            u("previousNdcToView", TEMPORAL_PREVIOUS_NDC_TO_VIEW),
            u("temporalInfo", TEMPORAL_INFO),
            u("historyValid", TEMPORAL_HISTORY_VALID),
            u("temporalCurve", TEMPORAL_CURVE),
            u("blurredFrames", TEMPORAL_BLURRED_FRAMES),
        ],
        &[
            s("texCurrent", INPUT),
            s("texDepth", SECOND_INPUT),
            s("texHistory", THIRD_INPUT),
            s("texRaw", TEMPORAL_RAW),
        ],
    ),
];

/// Differences between `program`'s active uniforms and `interface`: an active uniform the table
/// lacks or places elsewhere, a sampler on another unit, and a declared uniform the program does
/// not have (a typo in the table). Empty when they agree.
pub fn check_program(
    gl: &glow::Context,
    program: glow::Program,
    interface: &ProgramInterface,
) -> Vec<String> {
    use glow::HasContext;
    let mut problems = Vec::new();
    let mut seen = Vec::new();
    let file = interface.frag;
    // SAFETY: queries on a linked program of the current context.
    unsafe {
        for i in 0..gl.get_active_uniforms(program) {
            let Some(active) = gl.get_active_uniform(program, i) else {
                continue;
            };
            let name = active.name.trim_end_matches("[0]").to_string();
            let Some(location) = gl.get_uniform_location(program, &active.name) else {
                continue;
            };
            let location = location.0 as i32;
            let is_sampler = matches!(
                active.utype,
                glow::SAMPLER_2D | glow::SAMPLER_2D_SHADOW | glow::SAMPLER_CUBE | glow::SAMPLER_3D
            );
            if is_sampler {
                let mut unit = [0i32];
                gl.get_uniform_i32(
                    program,
                    &glow::NativeUniformLocation(location as u32),
                    &mut unit,
                );
                match interface.samplers.iter().find(|s| s.name == name) {
                    Some(s) if s.binding as i32 == unit[0] => {}
                    Some(s) => problems.push(format!(
                        "{file}: sampler {name} is on unit {}, the interface says {}",
                        unit[0], s.binding
                    )),
                    None => problems.push(format!(
                        "{file}: sampler {name} (unit {}) is not in the interface",
                        unit[0]
                    )),
                }
            } else {
                match interface.uniforms.iter().find(|u| u.name == name) {
                    Some(u) if u.location == location => {}
                    Some(u) => problems.push(format!(
                        "{file}: uniform {name} is at location {location}, the interface says {}",
                        u.location
                    )),
                    None => problems.push(format!(
                        "{file}: uniform {name} (location {location}) is not in the interface"
                    )),
                }
            }
            seen.push(name);
        }
    }
    let declared = interface
        .uniforms
        .iter()
        .map(|u| u.name)
        .chain(interface.samplers.iter().map(|s| s.name));
    for name in declared {
        if !seen.iter().any(|s| s == name) {
            problems.push(format!(
                "{file}: the interface lists {name}, which the program does not use"
            ));
        }
    }
    problems
}
