//! Putting the occlusion into the picture: the lesson's blend (`simple.frag` reading an R8 texture
//! swizzled to (0, 0, 0, occlusion)), the same limited to geometry (sky left alone), and the tinted
//! blend with a power (`ao/composite_tint.frag`).

use crate::gl::pass_state::{Blend, Depth};
use crate::gl::{FramebufferObject, Gl, MeshBuffer, PassState, ProgramObject, Texture};
use crate::math::DepthMode;
use crate::shader_interface::{binding, loc};

/// Darkens the main image: colour × (1 − occlusion), by blending a texture whose RGB reads 0 and A
/// reads the occlusion. The main FBO's bind sets the viewport (the printed listing lost it).
pub fn blend(
    gl: &Gl,
    simple: &ProgramObject,
    occlusion: &Texture,
    main: &FramebufferObject,
    meshes: &MeshBuffer,
) {
    PassState::FULLSCREEN
        .with_blend(Blend::ALPHA)
        .apply(gl, None);
    draw_swizzled(simple, occlusion, main, meshes);
}

/// `blend` limited to pixels where geometry was drawn: the quad sits at the depth buffer's cleared
/// value (`sky_depth`) and passes the test (`farther_func`, strict) only where something nearer was
/// written, so sky pixels (nothing to darken) are neither shaded nor blended.
pub fn blend_geometry_only(
    gl: &Gl,
    simple: &ProgramObject,
    occlusion: &Texture,
    main: &FramebufferObject,
    meshes: &MeshBuffer,
    sky_depth: f32,
    farther_func: u32,
) {
    surface_pixels_only(sky_depth, farther_func).apply(gl, None);
    draw_swizzled(simple, occlusion, main, meshes);
    PassState::FULLSCREEN.apply(gl, None);
}

fn draw_swizzled(
    simple: &ProgramObject,
    occlusion: &Texture,
    main: &FramebufferObject,
    meshes: &MeshBuffer,
) {
    occlusion.set_swizzle([glow::ZERO, glow::ZERO, glow::ZERO, glow::RED]);
    simple.use_program();
    main.bind();
    occlusion.bind(binding::INPUT);
    meshes.draw_plane_xy();
    // Other readers (debug views, tests) see plain R again.
    occlusion.set_swizzle([glow::RED, glow::GREEN, glow::BLUE, glow::ALPHA]);
}

/// Blends toward `tint` with visibility^`power` (`ao/composite_tint.frag`).
pub fn tinted(
    gl: &Gl,
    program: &ProgramObject,
    occlusion: &Texture,
    main: &FramebufferObject,
    meshes: &MeshBuffer,
    tint: [f32; 3],
    power: f32,
) {
    program.set_vec3(loc::AO_TINT, tint);
    program.set_f32(loc::AO_TINT_POWER, power);
    main.bind();
    PassState::FULLSCREEN
        .with_blend(Blend::ALPHA)
        .apply(gl, None);
    program.use_program();
    occlusion.bind(binding::INPUT);
    meshes.draw_plane_xy();
}

/// A blended full-screen quad that reaches only the pixels where a surface was drawn
/// (`surface_pixels_test`).
pub fn surface_pixels_only(sky_depth: f32, farther_func: u32) -> PassState {
    surface_pixels_test(sky_depth, farther_func).with_blend(Blend::ALPHA)
}

/// A full-screen quad that reaches only the pixels where a surface was drawn: the quad lies at the
/// sky's depth (`sky_depth`) and `farther_func` passes where it is farther than the stored depth, so
/// early depth testing drops the sky before the shader runs. Depth writes off.
pub fn surface_pixels_test(sky_depth: f32, farther_func: u32) -> PassState {
    PassState {
        depth: Depth::Test {
            func: farther_func,
            write: false,
        },
        depth_range: (sky_depth, sky_depth),
        ..PassState::FULLSCREEN
    }
}

/// The depth test that passes where the sky's depth (`mode.clear_value()`) lies farther than the
/// stored depth.
pub fn sky_farther(mode: DepthMode) -> u32 {
    if mode.reversed() {
        glow::LESS
    } else {
        glow::GREATER
    }
}
