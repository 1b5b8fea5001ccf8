// The environment atlas (render/EnvironmentAtlas.h): every map of image-based lighting in one
// 2D texture with one mip level and one layer. Dawn's frame cost grows with every sampled
// texture (a usage merge per texture when bundles execute) and with every subresource (a
// lazy-initialisation check per subresource at submit); the cube maps and the table as three
// textures were 37 subresources, the atlas is one.
//
// A cube map level is a region of six cells in a 3 x 2 grid, face f at column f % 3, row f / 3,
// in WebGPU's face order and orientation (environment_common.wgsl). Each cell is the face's
// texels, unchanged, inside a one-texel border that holds the face's plane continued past its
// edges (the radiance toward those directions), so hardware bilinear filtering near an edge
// blends the right radiance: seamless, as cube sampling is. The BRDF table is a region of one
// cell whose border repeats its edge (clamp to edge).

// Where the regions lie (EnvironmentAtlasUniform in C++, part of the lighting uniform): each as
// vec4f(first texel x, y, face size in texels, unused), borders included in the region.
struct EnvironmentAtlasLayout {
    inverseSize: vec2f,  // 1 / the atlas's width and height.
    unused: vec2f,
    irradiance: vec4f,
    brdf: vec4f,
    specular: array<vec4f, 8>,  // One per roughness level.
}

struct CubeFaceUv {
    face: u32,
    uv: vec2f,  // 0..1 across the face, v growing downwards like texture rows.
}

// The face a direction is looked up on and where: the inverse of cubeDirection.
fn cubeFaceUv(direction: vec3f) -> CubeFaceUv {
    let a = abs(direction);
    var result: CubeFaceUv;
    var st: vec2f;
    var major: f32;
    if (a.x >= a.y && a.x >= a.z) {
        major = a.x;
        result.face = select(1u, 0u, direction.x >= 0.0);
        st = vec2f(select(direction.z, -direction.z, direction.x >= 0.0), -direction.y);
    } else if (a.y >= a.z) {
        major = a.y;
        result.face = select(3u, 2u, direction.y >= 0.0);
        st = vec2f(direction.x, select(-direction.z, direction.z, direction.y >= 0.0));
    } else {
        major = a.z;
        result.face = select(5u, 4u, direction.z >= 0.0);
        st = vec2f(select(-direction.x, direction.x, direction.z >= 0.0), -direction.y);
    }
    result.uv = (st / major + 1.0) * 0.5;
    return result;
}

// Atlas texture coordinates of `uv` on `face` of a cube region.
fn atlasCubeCoordinates(region: vec4f, face: u32, uv: vec2f, inverseAtlasSize: vec2f) -> vec2f {
    let cell = vec2f(f32(face % 3u), f32(face / 3u)) * (region.z + 2.0);
    return (region.xy + cell + 1.0 + uv * region.z) * inverseAtlasSize;
}

// Atlas texture coordinates of `uv` (0..1) in a one-cell region.
fn atlasTableCoordinates(region: vec4f, uv: vec2f, inverseAtlasSize: vec2f) -> vec2f {
    return (region.xy + 1.0 + uv * region.z) * inverseAtlasSize;
}
