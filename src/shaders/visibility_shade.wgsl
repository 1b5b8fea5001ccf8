// The visibility strategy's resolve: one dispatch per shading bin (one material; HAS_TANGENT as the
// bin says), a fixed grid of workgroups striding over the bin's 8x8 tiles (visibility_bins.wgsl),
// or over every tile where the scene has one bin (not binned), a thread per pixel of the tile, of
// any of the views side by side that the bins cover (the view slots of visibility_geometry.wgsl,
// under VIEW_SLOTS, which the strategy always sets). A thread shades each sample of its pixel whose
// triangle is in the bin and covers no earlier sample of the pixel (with several samples, each
// distinct triangle of a pixel once), into the texel of that sample. It rebuilds the triangle from
// the visibility buffer's id, its perspective-correct barycentrics at the pixel centre (where
// multisampled hardware shades too) and their screen-space derivatives (texture LOD, the tangent
// frame), interpolates what mesh.wgsl's vertex shader outputs, and shades with the same code as
// mesh.wgsl's fragment shader (surface_shading.wgsl), sampling with explicit gradients
// (SAMPLE_GRADIENT). COMPOSED (frames composed in compute at one sample): the colour goes straight
// into the composed frame (visibility_composed.wgsl), not to the shaded texture. Materials binning
// the same textures and samplers share a bin (render/visibility/MaterialBins.h): each pixel's
// material comes from the bin's table (`material`, a private copy), the textures from the bind
// group of the bin's first material.
// Variants: MATERIAL_TEXTURES, HAS_TANGENT, COMPOSED (HALF_OUTPUT).
#include "frame.wgsl"
#include "scene_lighting.wgsl"
#include "brdf.wgsl"
#include "material.wgsl"
#include "material_samples.wgsl"
#include "surface_shading.wgsl"
#include "visibility_geometry.wgsl"
#include "visibility_samples.wgsl"
#include "visibility_pixel.wgsl"

// The start of the bin's record (visibility_bins.wgsl's Bin), read as a uniform.
struct Bin {
    count: u32,  // Tiles.
    id: u32,
    first: u32,
    // 1: the scene's only bin, whose record the strategy writes: no tile is listed, the shading
    // takes every tile of its views and writes their uncovered pixels' background (COMPOSED),
    // which the binning does otherwise. On the H100 the binning took 0.02 ms of a 1280x720 frame.
    everyTile: u32,
}

@group(1) @binding(4) var<storage, read> units: array<vec2u>;
@group(1) @binding(5) var<storage, read> visibility: array<vec2u>;
@group(1) @binding(6) var<storage, read> tiles: array<u32>;
@group(1) @binding(7) var<uniform> bin: Bin;
// The bin's materials (render/visibility/MaterialBins.h): copies of their uniforms, a slot each,
// in the block the strategy binds for the bin; a record's bin word names the slot.
struct MaterialSlot {
    @size(1024) material: Material,  // MaterialBins::kSlotBytes.
}
@group(1) @binding(10) var<uniform> binMaterials: array<MaterialSlot, 64>;  // kBinMaterials.
// The pixel's material, which material.wgsl's functions read.
var<private> material: Material;
#if COMPOSED
#include "visibility_composed.wgsl"
@group(1) @binding(8) var composedFrame: ComposedFrame;
@group(1) @binding(9) var<uniform> composition: Composition;
#else
@group(1) @binding(8) var shaded: texture_storage_2d_array<rgba16float, write>;
#endif

// Barycentrics of the pixel centre and their change one pixel right and one pixel down.
struct Barycentrics {
    value: vec3f,
    dx: vec3f,
    dy: vec3f,
}

// Perspective-correct barycentrics from the clip positions: 1/w and attribute/w are linear in
// normalised device coordinates, and one pixel is a fixed step there.
fn barycentrics(c0: vec4f, c1: vec4f, c2: vec4f, ndc: vec2f, step: vec2f) -> Barycentrics {
    let inverseW = 1.0 / vec3f(c0.w, c1.w, c2.w);
    let n0 = c0.xy * inverseW.x;
    let n1 = c1.xy * inverseW.y;
    let n2 = c2.xy * inverseW.z;
    let inverseDet = 1.0 / determinant(mat2x2f(n2 - n1, n0 - n1));
    let ddx = vec3f(n1.y - n2.y, n2.y - n0.y, n0.y - n1.y) * inverseDet * inverseW;
    let ddy = vec3f(n2.x - n1.x, n0.x - n2.x, n1.x - n0.x) * inverseDet * inverseW;
    let delta = ndc - n0;
    let numerator = vec3f(inverseW.x, 0.0, 0.0) + delta.x * ddx + delta.y * ddy;
    let interpolatedInverseW = numerator.x + numerator.y + numerator.z;
    var result: Barycentrics;
    result.value = numerator / interpolatedInverseW;
    let numeratorX = numerator + step.x * ddx;
    let numeratorY = numerator + step.y * ddy;
    result.dx = numeratorX / (numeratorX.x + numeratorX.y + numeratorX.z) - result.value;
    result.dy = numeratorY / (numeratorY.x + numeratorY.y + numeratorY.z) - result.value;
    return result;
}

fn mix3(b: vec3f, a0: vec4f, a1: vec4f, a2: vec4f) -> vec4f {
    return a0 * b.x + a1 * b.y + a2 * b.z;
}

// A fixed grid of workgroups strides over the bin's tiles: one direct dispatch per bin, as the
// raster passes (visibility_raster.wgsl says why).
@compute @workgroup_size(64)
fn shadeMain(@builtin(workgroup_id) group: vec3u, @builtin(num_workgroups) groups: vec3u,
             @builtin(local_invocation_index) lane: u32) {
#if VIEW_SLOTS
    // The samples, the target's width and the height are the same in every view; the group's
    // views follow its first, kSlotViews at most.
    let first = viewSlots[0].params;
    let groupWidth = min(first.targetWidth - first.viewportX, kSlotViews * first.viewportWidth);
#else
    let first = params;  // One view's parameters (the strategy sets slots).
    let groupWidth = first.viewportWidth;
#endif
    let samples = first.samples;
    let size = vec2u(first.targetWidth, first.viewportHeight);
    // Every tile of the group's views, from its first (which starts on a tile), row by row.
    let gridOrigin = vec2u(first.viewportX, first.viewportY) / 8u;
    let gridColumns = (groupWidth + 7u) / 8u;
    let tileCount = select(bin.count, gridColumns * ((size.y + 7u) / 8u), bin.everyTile != 0u);
    let offset = vec2u(lane % 8u, lane / 8u);
    for (var i = group.x; i < tileCount; i += groups.x) {
        var tile = gridOrigin + vec2u(i % gridColumns, i / gridColumns);
        if (bin.everyTile == 0u) {
            let listed = tiles[bin.first + i];
            tile = vec2u(listed & 0xffffu, listed >> 16u);
        }
        let pixel = tile * 8u + offset;
        if (any(pixel >= size)) {
            continue;
        }
        let taken = distinctSamples((pixel.y * size.x + pixel.x) * samples, samples);
#if COMPOSED
        if (bin.everyTile != 0u && taken.mask == 0u) {
            storeComposed(pixel, vec4f(0.0));  // Uncovered: the background.
            continue;
        }
#endif
        for (var sample = 0u; sample < samples; sample++) {
            if ((taken.mask & (1u << sample)) != 0u) {
                shadeSample(pixel, sample, taken.ids[sample]);
            }
        }
    }
}

// Shades `sample` of `pixel` with triangle `id` where that triangle is in the bin.
fn shadeSample(pixel: vec2u, sample: u32, id: u32) {
#if VIEW_SLOTS
    selectViewOf(pixel);
#endif
    let unit = units[id / kUnitTriangles];
    let item = loadItem(unit.x);
    let record = item.record;
    let binWord = tables[record + kBin];
    if ((binWord & kBinMask) != bin.id) {
        return;  // Another bin's, which a dispatch of its own shades.
    }
    material = binMaterials[binWord >> kBinSlotShift].material;
    let triangle = unitTriangle(unit, id);
    let transform = instances[item.slot];
    let i0 = vertexIndex(record, triangle, 0u);
    let i1 = vertexIndex(record, triangle, 1u);
    let i2 = vertexIndex(record, triangle, 2u);
    let w0 = worldPosition(record, transform, i0);
    let w1 = worldPosition(record, transform, i1);
    let w2 = worldPosition(record, transform, i2);
    let c0 = clipPosition(w0);
    let c1 = clipPosition(w1);
    let c2 = clipPosition(w2);

    let halfSize = vec2f(f32(params.viewportWidth), f32(params.viewportHeight)) * 0.5;
    let viewport = vec2f(f32(params.viewportX), f32(params.viewportY));
    let step = vec2f(1.0, -1.0) / halfSize;
    let centre = vec2f(pixel) + 0.5 - viewport;
    let ndc = vec2f(centre.x / halfSize.x - 1.0, 1.0 - centre.y / halfSize.y);
    var b = barycentrics(c0, c1, c2, ndc, step);
    // Derivatives as a fragment shader's coarse ones: those of the 2x2 quad's first pixel, so
    // that textures pick the same level of detail as the hardware path.
    let quad = vec2f(pixel & vec2u(~1u)) + 0.5 - viewport;
    let quadNdc = vec2f(quad.x / halfSize.x - 1.0, 1.0 - quad.y / halfSize.y);
    let atQuad = barycentrics(c0, c1, c2, quadNdc, step);
    b.dx = atQuad.dx;
    b.dy = atQuad.dy;

    let worldPosition = mix3(b.value, w0, w1, w2).xyz;
    let positionDx = mix3(b.dx, w0, w1, w2).xyz;
    let positionDy = mix3(b.dy, w0, w1, w2).xyz;

    let normals = attributeAt(record, kNormal);
    let normal = mix3(b.value, loadAttribute(normals, i0, vec4f(0.0)),
                      loadAttribute(normals, i1, vec4f(0.0)),
                      loadAttribute(normals, i2, vec4f(0.0))).xyz;
    let worldNormal = (transform.normal * vec4f(normal, 0.0)).xyz;

    let uvs0 = attributeAt(record, kTexcoord0);
    let t0 = loadAttribute(uvs0, i0, vec4f(0.0));
    let t1 = loadAttribute(uvs0, i1, vec4f(0.0));
    let t2 = loadAttribute(uvs0, i2, vec4f(0.0));
    // mesh.wgsl: TEXCOORD_1 falls back to TEXCOORD_0 (not loaded twice).
    var s0 = t0;
    var s1 = t1;
    var s2 = t2;
    let uvs1 = attributeAt(record, kTexcoord1);
    if (uvs1.format != 0u) {
        s0 = loadAttribute(uvs1, i0, vec4f(0.0));
        s1 = loadAttribute(uvs1, i1, vec4f(0.0));
        s2 = loadAttribute(uvs1, i2, vec4f(0.0));
    }
    let uv0 = mix3(b.value, t0, t1, t2).xy;
    let uv1 = mix3(b.value, s0, s1, s2).xy;
    var gradients: UvGradients;
    gradients.dx0 = mix3(b.dx, t0, t1, t2).xy;
    gradients.dy0 = mix3(b.dy, t0, t1, t2).xy;
    gradients.dx1 = mix3(b.dx, s0, s1, s2).xy;
    gradients.dy1 = mix3(b.dy, s0, s1, s2).xy;

    let colors = attributeAt(record, kColor);
    let color = mix3(b.value, loadAttribute(colors, i0, vec4f(1.0)),
                     loadAttribute(colors, i1, vec4f(1.0)),
                     loadAttribute(colors, i2, vec4f(1.0)));

    let linear = mat3x3f(transform.world[0].xyz, transform.world[1].xyz, transform.world[2].xyz);
    let mirrored = determinant(linear) < 0.0;
    var tangent = vec4f(0.0);
#if HAS_TANGENT
    let tangents = attributeAt(record, kTangent);
    let vertexTangent = mix3(b.value, loadAttribute(tangents, i0, vec4f(0.0)),
                             loadAttribute(tangents, i1, vec4f(0.0)),
                             loadAttribute(tangents, i2, vec4f(0.0)));
    tangent = vec4f(linear * vertexTangent.xyz, vertexTangent.w * select(1.0, -1.0, mirrored));
#endif
    // Counter-clockwise in normalised device coordinates faces the viewer, unless the instance
    // mirrors (its pipelines take the other front face). Decided by the homogeneous determinant
    // (visibility_raster.wgsl's facesTheCamera): past a vertex behind the camera the projected
    // corners flip, the winding of the part in view does not.
    let counterClockwise = determinant(mat3x3f(c0.xyw, c1.xyw, c2.xyw)) > 0.0;
    let frontFacing = counterClockwise != mirrored;

    let samples = sampleMaterial(uv0, uv1, gradients);
    let baseColor = material.baseColorFactor * color * samples.baseColor;
    let result = shadeSurface(worldPosition, worldNormal, tangent, frontFacing, baseColor,
                              samples, positionDx, positionDy, gradients.dx0, gradients.dy0,
                              vec3f(1.0));  // Transmissive materials are drawn in hardware.
#if COMPOSED
    storeComposed(pixel, displayColor(result));  // One sample: the pixel's colour.
#else
    textureStore(shaded, pixel, sample, displayColor(result));
#endif
}
