//! Reading pixels back from GL (rows bottom-up) into images and value buffers (rows top-down).

use glow::HasContext;

/// Reads RGBA8 pixels of a framebuffer (`None` = default) and returns them top-down.
pub fn read_rgba8(
    gl: &glow::Context,
    fbo: Option<glow::Framebuffer>,
    width: u32,
    height: u32,
) -> image::RgbaImage {
    let mut data = vec![0u8; (width * height * 4) as usize];
    unsafe {
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, fbo);
        if fbo.is_none() {
            gl.read_buffer(glow::BACK);
        }
        gl.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
        gl.read_pixels(
            0,
            0,
            width as i32,
            height as i32,
            glow::RGBA,
            glow::UNSIGNED_BYTE,
            glow::PixelPackData::Slice(Some(&mut data)),
        );
        gl.bind_framebuffer(glow::READ_FRAMEBUFFER, None);
    }
    flip_rows(&mut data, (width * 4) as usize, height as usize);
    image::RgbaImage::from_raw(width, height, data).expect("buffer size matches")
}

/// GL rows are bottom-up; images are top-down.
pub fn flip_rows<T: Copy>(data: &mut [T], row_len: usize, rows: usize) {
    for y in 0..rows / 2 {
        let (a, b) = data.split_at_mut((rows - 1 - y) * row_len);
        a[y * row_len..(y + 1) * row_len].swap_with_slice(&mut b[..row_len]);
    }
}
