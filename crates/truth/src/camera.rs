//! Camera rays: the scene's projection and view in f64, the same matrices the harness gives
//! the pack, and stratified sample positions within a pixel.

use glam::{DMat3, DMat4, DVec2, DVec3, DVec4, Vec4Swizzles};
use tidepack_scene::Scene;

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    projection_inverse: DMat4,
    /// gbufferModelViewInverse's rotation: view axes to world axes.
    view_to_world: DMat3,
    pub width: usize,
    pub height: usize,
}

impl Camera {
    pub fn of(scene: &Scene) -> Camera {
        Camera {
            projection_inverse: scene.projection().inverse(),
            view_to_world: DMat3::from_mat4(scene.model_view().inverse()),
            width: scene.width() as usize,
            height: scene.height() as usize,
        }
    }

    /// The unit direction (world axes, from the eye) through screen position `uv` in [0, 1]²,
    /// v up: the line through the point at NDC depth 0, as composite's `viewFromScreen` puts it.
    pub fn direction(&self, uv: DVec2) -> DVec3 {
        let clip = DVec4::new(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, 0.0, 1.0);
        let view = self.projection_inverse * clip;
        (self.view_to_world * (view.xyz() / view.w)).normalize()
    }

    /// Sample (i, j) of an n × n stratified grid in pixel (x, y), y counted from the bottom:
    /// the centres of the sub-cells, so one sample is the pixel centre the composite shades.
    pub fn sample(&self, x: usize, y: usize, i: u32, j: u32, n: u32) -> DVec2 {
        let n = n.max(1) as f64;
        DVec2::new((x as f64 + (i as f64 + 0.5) / n) / self.width as f64, (y as f64 + (j as f64 + 0.5) / n) / self.height as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_of_the_screen_looks_along_the_cameras_yaw_and_pitch() {
        let scene = Scene::load(std::path::Path::new("case4_above_near")).unwrap();
        let camera = Camera::of(&scene);
        // yaw 180 looks towards -z; pitch 38 looks down.
        let d = camera.direction(DVec2::splat(0.5));
        let pitch = 38f64.to_radians();
        assert!((d - DVec3::new(0.0, -pitch.sin(), -pitch.cos())).length() < 1e-12, "{d}");
        // The top of the screen is half the vertical field of view above the centre.
        let up = camera.direction(DVec2::new(0.5, 1.0));
        assert!((up.angle_between(d) - 35f64.to_radians()).abs() < 1e-12);
        assert_eq!(camera.sample(3, 4, 0, 0, 1), DVec2::new(3.5 / 640.0, 4.5 / 360.0));
    }
}
