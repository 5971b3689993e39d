//! One file per AO method, each owning its shader name, programs, uniform counts and presets.

pub mod angle_based;
pub mod crytek;
pub mod gtao;
pub mod hbao;
pub mod hemisphere;
pub mod sao;
pub mod sao_lesson;
pub mod vbao;
