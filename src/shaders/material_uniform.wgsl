// The material's factors as the draws bind them (group 2, binding 0 of
// BindGroupLayouts::material), which material.wgsl's functions read. The visibility strategy's
// shading declares a per-pixel copy from its bins' table instead (visibility_shade.wgsl).
@group(2) @binding(0) var<uniform> material: Material;
