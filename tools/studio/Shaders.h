#pragma once
// GLSL 3.30 core sources of the studio's renderer.

namespace netsculpt::studio::shaders {

/// Bars, knots (as points), the grid and guide lines: a colour per vertex, faded into the
/// background with distance so depth reads at a glance.
inline constexpr const char* kLinesVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColour;
uniform mat4 uViewProjection;
uniform mat4 uView;
uniform vec3 uFogColour;
uniform vec2 uFogRange;
uniform float uPointSize;
uniform float uBrighten;
uniform ivec2 uBrightVertices; // [first, end): the vertices brightened by uBrighten
out vec3 vColour;
void main() {
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
    gl_PointSize = uPointSize;
    float depth = -(uView * vec4(aPosition, 1.0)).z;
    float fog = clamp((depth - uFogRange.x) / (uFogRange.y - uFogRange.x), 0.0, 1.0);
    bool bright = gl_VertexID >= uBrightVertices.x && gl_VertexID < uBrightVertices.y;
    vColour = mix(mix(aColour, uFogColour, 0.5 * fog), vec3(1.0), bright ? uBrighten : 0.0);
}
)";

inline constexpr const char* kLinesFragment = R"(#version 330 core
in vec3 vColour;
uniform float uAlpha;
out vec4 fragColour;
void main() { fragColour = vec4(vColour, uAlpha); }
)";

/// Thick lines: the geometry shader turns each segment into a screen-space quad of uWidth pixels
/// with square caps; the fragment shader shades it like a tube.
inline constexpr const char* kThickVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
void main() { gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";

inline constexpr const char* kThickGeometry = R"(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
uniform vec2 uViewport;
uniform float uWidth;
out float vAcross;
void main() {
    vec4 a = gl_in[0].gl_Position;
    vec4 b = gl_in[1].gl_Position;
    const float nearW = 1e-4;
    if (a.w < nearW && b.w < nearW) return;
    if (a.w < nearW) a = mix(a, b, (nearW - a.w) / (b.w - a.w));
    if (b.w < nearW) b = mix(b, a, (nearW - b.w) / (a.w - b.w));
    vec2 halfViewport = 0.5 * uViewport;
    vec2 sa = a.xy / a.w * halfViewport;
    vec2 sb = b.xy / b.w * halfViewport;
    vec2 dir = sb - sa;
    dir = length(dir) > 1e-6 ? normalize(dir) : vec2(1.0, 0.0);
    vec2 side = vec2(-dir.y, dir.x) * 0.5 * uWidth / halfViewport;
    vec2 cap = dir * 0.5 * uWidth / halfViewport;
    gl_Position = vec4(a.xy + (-cap + side) * a.w, a.zw); vAcross = 1.0; EmitVertex();
    gl_Position = vec4(a.xy + (-cap - side) * a.w, a.zw); vAcross = -1.0; EmitVertex();
    gl_Position = vec4(b.xy + (cap + side) * b.w, b.zw); vAcross = 1.0; EmitVertex();
    gl_Position = vec4(b.xy + (cap - side) * b.w, b.zw); vAcross = -1.0; EmitVertex();
    EndPrimitive();
}
)";

inline constexpr const char* kThickFragment = R"(#version 330 core
in float vAcross;
uniform vec4 uColour;
out vec4 fragColour;
void main() {
    float s = sqrt(max(0.0, 1.0 - vAcross * vAcross));
    vec3 shade = uColour.rgb * (0.35 + 0.65 * s) + vec3(0.35) * pow(s, 12.0);
    fragColour = vec4(shade, uColour.a);
}
)";

/// Sphere impostors, one instance per handle: a camera-facing quad shaded as a lit sphere.
inline constexpr const char* kSphereVertex = R"(#version 330 core
layout(location = 0) in vec2 aCorner;
layout(location = 1) in vec4 aCentreRadius;
layout(location = 2) in vec4 aColour;
uniform mat4 uView;
uniform mat4 uProjection;
out vec2 vCorner;
out vec4 vColour;
void main() {
    vec4 centre = uView * vec4(aCentreRadius.xyz, 1.0);
    centre.xy += aCorner * aCentreRadius.w;
    centre.z += aCentreRadius.w; // the front of the sphere, so bars through it do not cut it
    gl_Position = uProjection * centre;
    vCorner = aCorner;
    vColour = aColour;
}
)";

inline constexpr const char* kSphereFragment = R"(#version 330 core
in vec2 vCorner;
in vec4 vColour;
out vec4 fragColour;
void main() {
    float r2 = dot(vCorner, vCorner);
    if (r2 > 1.0) discard;
    vec3 n = vec3(vCorner, sqrt(1.0 - r2));
    vec3 light = normalize(vec3(-0.4, 0.6, 0.8));
    float diffuse = max(dot(n, light), 0.0);
    float specular = pow(max(dot(reflect(-light, n), vec3(0.0, 0.0, 1.0)), 0.0), 24.0);
    float rim = smoothstep(0.75, 1.0, r2) * 0.25;
    fragColour = vec4(vColour.rgb * (0.30 + 0.70 * diffuse) + vec3(0.45 * specular) - rim, vColour.a);
}
)";

/// A full-screen vertical gradient: a quad (no vertex buffer: the corners come from gl_VertexID)
/// whose colours are interpolated, cheaper on a software renderer than computing it per pixel.
inline constexpr const char* kBackgroundVertex = R"(#version 330 core
uniform vec3 uTop;
uniform vec3 uBottom;
out vec3 vColour;
void main() {
    vec2 p = vec2(float(gl_VertexID & 1) * 2.0 - 1.0, float(gl_VertexID & 2) - 1.0);
    vColour = p.y > 0.0 ? uTop : uBottom;
    gl_Position = vec4(p, 0.999, 1.0);
}
)";

inline constexpr const char* kBackgroundFragment = R"(#version 330 core
in vec3 vColour;
out vec4 fragColour;
void main() { fragColour = vec4(vColour, 1.0); }
)";

} // namespace netsculpt::studio::shaders
