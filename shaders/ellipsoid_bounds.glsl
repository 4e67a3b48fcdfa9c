#version 450 core
// Where an ellipsoid lands on screen, exactly: the bounding box of its
// projected silhouette from the quadric's dual (Sigg et al. 2006, "GPU-Based
// Ray-Casting of Quadratic Surfaces"). The ellipsoid x = centre + a u, |u| <= 1,
// goes to clip space by the rows T_x, T_y, T_w of the projection applied to
// [a | centre]; the NDC line x = k touches it where the dual quadric
// R = T diag(1,1,1,-1) T^T gives r_xx - 2 k r_xw + k^2 r_ww = 0. A library
// without a stage, linked into ellipsoid_shape.vert.glsl and
// ellipsoid_shape.comp.glsl (sphere_bounds.glsl bounds spheres).

// Where a bound may lie at most, in NDC (as sphere_bounds.glsl).
const float ELLIPSOID_FAR_OUTSIDE = 4.0;

float dual(vec4 p, vec4 q)
{
    return dot(p.xyz, q.xyz) - p.w * q.w;
}

vec2 tangent_lines(vec4 t, vec4 tw, float r_ww)
{
    float r_tw = dual(t, tw);
    float root = sqrt(max(r_tw * r_tw - dual(t, t) * r_ww, 0.0));
    vec2 k = vec2(r_tw + root, r_tw - root) / r_ww;
    return clamp(vec2(min(k.x, k.y), max(k.x, k.y)), -ELLIPSOID_FAR_OUTSIDE, ELLIPSOID_FAR_OUTSIDE);
}

// The NDC box (x_lo, x_hi, y_lo, y_hi) of the ellipsoid x = centre + a u in
// view space, seen through focal lengths `focal` (P[0][0], P[1][1]); false
// when it reaches the eye's plane, where its projection is unbounded.
bool projected_ellipsoid_bounds(vec3 centre, mat3 a, vec2 focal, out vec4 box)
{
    // Row i of a (columns a[0..2]) with the centre's component i.
    vec4 tw = -vec4(a[0].z, a[1].z, a[2].z, centre.z);
    vec4 tx = focal.x * vec4(a[0].x, a[1].x, a[2].x, centre.x);
    vec4 ty = focal.y * vec4(a[0].y, a[1].y, a[2].y, centre.y);
    float r_ww = dual(tw, tw);
    box = vec4(0.0);
    if (r_ww >= 0.0)
        return false;
    box = vec4(tangent_lines(tx, tw, r_ww), tangent_lines(ty, tw, r_ww));
    return true;
}
