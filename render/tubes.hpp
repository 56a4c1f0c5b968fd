#pragma once
// Branching plants in 3-D: each branch a shaded truncated cone, seen in
// perspective through a camera, with a depth test and simple lighting.
// World space is y up (unlike the pixel space of the rest of render/); only
// the viewport, a pixel rectangle of the canvas, is in top-left y-down pixels.
//
// Each tube is drawn as a capsule: its cone plus a hemisphere of the end's
// radius over each end, so consecutive branches join without gaps or seams
// (the hidden half of each end sphere is left out). One instanced draw call
// draws them all. Flat facets (leaves, petals) go into the same picture,
// depth-tested against the tubes, under the same light and camera; a facet
// is lit on the side the eye sees, as a thin leaf is.

#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "render/surface.hpp"

namespace render {

struct Tube {
    glm::vec3 a, b;              // end points, world units
    float radius_a, radius_b;    // radius at a and at b, world units, >= 0
    glm::vec4 colour;            // straight RGBA; meant opaque (the depth test does not sort)
};

struct Facet {
    glm::vec3 a, b, c;           // corners, world units; a facet with no area draws nothing
    glm::vec4 colour;            // straight RGBA; meant opaque, as a tube's
    // The surface's normals at a, b and c, for smooth shading (an
    // isosurface's); zero: the facet's own, flat (a leaf's).
    glm::vec3 na{0}, nb{0}, nc{0};
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

// The twelve edges of the box lo..hi, each a tube of `radius` and `colour`:
// along x, then y, then z.
std::vector<Tube> box_edges(glm::vec3 lo, glm::vec3 hi, float radius, glm::vec4 colour);

// The box (lo, hi) that holds every tube, radii included.
std::pair<glm::vec3, glm::vec3> tube_bounds(const std::vector<Tube>& tubes);

// What frame_balls frames: a point with a radius (a tube's end, a leaf's corner with 0).
struct Ball {
    glm::vec3 centre;            // world units
    float radius;                // world units, >= 0
};

// The balls of a drawing: each tube's two ends and each facet's corners.
std::vector<Ball> balls_of(const std::vector<Tube>& tubes, const std::vector<Facet>& facets);

// Where the balls land through `camera` in a viewport of `aspect`: the
// least box holding them, in normalised device coordinates (-1..1 across the
// viewport, y up). A ball counts as its centre widened by its radius at its
// depth: exact on the line of sight, a little short of a sphere's outline
// towards the viewport's edges.
struct Extent {
    glm::vec2 lo, hi;
};
Extent projected_extent(std::span<const Ball> balls, const Camera& camera, float aspect);

// Frames the balls tighter than frame_bounds frames their box: from the same
// direction, looking at the point and from the distance at which their
// projected extent is centred in the viewport and fills `fill` of its height
// or of its width, whichever is reached first. Not nearer than min_distance
// (a turntable keeps one distance all the way round). The balls must be
// finite; none gives a camera on the origin at a unit distance.
Camera frame_balls(std::span<const Ball> balls, float azimuth_degrees, float elevation_degrees, float aspect,
                   float fill = 0.94f, float min_distance = 0, float fov_degrees = 35);

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

// Draws the tubes and the facets into `viewport` (canvas pixels, rounded to
// whole pixels) with the depth test on. Depth is cleared inside the viewport first, so a
// call is self-contained, as 2-D drawing is: what it draws covers what was
// there. `sides` is the number of facets around a tube (smooth normals hide
// them). Throws std::logic_error if the canvas has no depth buffer and
// std::invalid_argument for a negative or non-finite radius, sides outside
// 3..256 or an empty viewport, and for a non-finite facet corner. Leaves
// depth test, culling and scissor off and the viewport on the whole canvas,
// as 2-D drawing expects.
void draw_tubes(Surface& surface, const Rect& viewport, const std::vector<Tube>& tubes,
                const std::vector<Facet>& facets, const Camera& camera, const Light& light = {}, int sides = 12);
// Tubes alone.
void draw_tubes(Surface& surface, const Rect& viewport, const std::vector<Tube>& tubes, const Camera& camera,
                const Light& light = {}, int sides = 12);

}  // namespace render
