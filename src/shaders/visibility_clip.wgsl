// Clipping for the compute raster (visibility_raster.wgsl's triangles listed whole): a triangle
// cut by the near and far planes and a guard band, in homogeneous coordinates.

// The guard band that clipped triangles are cut to: this many pixels past each edge of the
// viewport. Their pieces' vertices then lie within 2^22 (in 1/256 pixel) of the viewport's
// pixels, as those of triangles up to kMaxWorkgroupPixels across that touch it (wideEdge).
const kGuardPixels = 8192.0;

// A convex polygon of clip positions: a triangle cut by the six planes of clipPolygon, each of
// which adds at most one vertex.
struct ClipPolygon {
    count: u32,
    v: array<vec4f, 9>,
}

// The signed distance of `v` from clip plane `plane` (positive inside): near, far, then the
// guard band's left, right, bottom and top at `guard` (normalised device coordinates).
fn planeDistance(v: vec4f, plane: u32, guard: vec2f) -> f32 {
    switch plane {
        case 0u: {
            return v.z;
        }
        case 1u: {
            return v.w - v.z;
        }
        case 2u: {
            return v.x + guard.x * v.w;
        }
        case 3u: {
            return guard.x * v.w - v.x;
        }
        case 4u: {
            return v.y + guard.y * v.w;
        }
        default: {
            return guard.y * v.w - v.y;
        }
    }
}

// The part of triangle (c0, c1, c2) inside the near and far planes and the guard band of a
// viewport of `viewport` pixels
// (Sutherland-Hodgman, in homogeneous coordinates, so that vertices behind the camera clip as
// the hardware clips them). Its fan from the first vertex covers it: pieces that share their
// inner edges exactly, which the top-left rule covers once.
fn clipPolygon(c0: vec4f, c1: vec4f, c2: vec4f, viewport: vec2f) -> ClipPolygon {
    let half = viewport * 0.5;
    let guard = (half + kGuardPixels) / half;
    var polygon: ClipPolygon;
    polygon.count = 3u;
    polygon.v[0] = c0;
    polygon.v[1] = c1;
    polygon.v[2] = c2;
    for (var plane = 0u; plane < 6u && polygon.count >= 3u; plane++) {
        var cut: ClipPolygon;
        cut.count = 0u;
        for (var i = 0u; i < polygon.count; i++) {
            let a = polygon.v[i];
            let b = polygon.v[select(i + 1u, 0u, i + 1u == polygon.count)];
            let da = planeDistance(a, plane, guard);
            let db = planeDistance(b, plane, guard);
            if (da >= 0.0) {
                cut.v[cut.count] = a;
                cut.count++;
            }
            if ((da >= 0.0) != (db >= 0.0)) {
                // From the vertex inside, as the hardware's clipper interpolates: the same edge
                // whichever way round the polygon meets it.
                let inside = select(b, a, da >= 0.0);
                let outside = select(a, b, da >= 0.0);
                let din = max(da, db);
                cut.v[cut.count] = inside + (outside - inside) * (din / (din - min(da, db)));
                cut.count++;
            }
        }
        polygon = cut;
    }
    return polygon;
}
