#pragma once
// Branching plants in 3-D: each branch a shaded truncated cone, seen in
// perspective through a camera, with a depth test and simple lighting.
// World space is y up (unlike the pixel space of the rest of render/); only
// the viewport, a pixel rectangle of the canvas, is in top-left y-down pixels.
//
// Each tube is drawn as a capsule: its cone plus a hemisphere of the end's
// radius over each end, so consecutive branches join without gaps or seams
// (the hidden half of each end sphere is left out). One instanced draw call
// draws them all.

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/canvas.hpp"

namespace render {

struct Tube {
    glm::vec3 a, b;              // end points, world units
    float radius_a, radius_b;    // radius at a and at b, world units, >= 0
    glm::vec4 colour;            // straight RGBA; meant opaque (the depth test does not sort)
};

struct Camera {
    glm::vec3 eye, target;       // where it stands and what it looks at, world units
    glm::vec3 up{0, 1, 0};       // which way is up on screen
    float fov_degrees = 35;      // vertical field of view
    float near = 0.1f, far = 1000;  // depth range, world units from the eye
};

// Frames the box lo..hi so that all of it is visible in a viewport of
// `aspect` (width / height): looks at the box's centre from azimuth degrees
// about y (0: from +z, 90: from +x) and elevation degrees above the
// horizontal (90: straight down), from the distance at which the box's
// corners just fit, with a small margin. near and far hug the box.
Camera frame_bounds(glm::vec3 lo, glm::vec3 hi, float azimuth_degrees, float elevation_degrees, float aspect,
                    float fov_degrees = 35);

// The box (lo, hi) that holds every tube, radii included.
std::pair<glm::vec3, glm::vec3> tube_bounds(const std::vector<Tube>& tubes);

// World to clip space: glm::perspective(fov, aspect, near, far) * glm::lookAt(eye, target, up).
glm::mat4 view_projection(const Camera& camera, float aspect);

// Where a world point lands in `viewport`, in canvas pixels (top-left origin, y down).
glm::vec2 project(const Camera& camera, const Rect& viewport, glm::vec3 point);

struct Light {
    glm::vec3 direction{-0.4f, 0.8f, 0.45f};  // towards the light, world space (need not be unit)
    float ambient = 0.3f;                     // share of the colour everywhere
    float diffuse = 0.7f;                     // share of the colour times cos(angle to the light) (Lambert)
    float specular = 0.15f;                   // white highlight (Blinn-Phong)
};

// Draws the tubes into `viewport` (canvas pixels, rounded to whole pixels)
// with the depth test on. Depth is cleared inside the viewport first, so a
// call is self-contained, as 2-D drawing is: what it draws covers what was
// there. `sides` is the number of facets around a tube (smooth normals hide
// them). Throws std::logic_error if the canvas has no depth buffer and
// std::invalid_argument for a negative or non-finite radius, sides outside
// 3..256 or an empty viewport. Leaves depth test, culling and scissor off
// and the viewport on the whole canvas, as 2-D drawing expects.
void draw_tubes(Surface& surface, const Rect& viewport, const std::vector<Tube>& tubes, const Camera& camera,
                const Light& light = {}, int sides = 12);

}  // namespace render
