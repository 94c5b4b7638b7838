// render/shaders.cpp: GLSL sources and program building.
#define GL_GLEXT_PROTOTYPES 1
#include "render/shaders.h"

#include <GL/osmesa.h>
#include <stdexcept>
#include <string>

namespace frontier::render
{
namespace
{

const char* const cLitVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel;
uniform mat4 uViewProj;
uniform mat4 uLightViewProj;
uniform float uNormalOffset;
out vec3 vWorld;
out vec3 vNormal;
out vec4 vLight;
void main()
{
    vec4 world = uModel * vec4(aPosition, 1.0);
    vec3 normal = normalize(mat3(uModel) * aNormal);
    vWorld = world.xyz;
    vNormal = normal;
    // Normal-offset shadow lookups keep lit surfaces from shadowing themselves (acne).
    vLight = uLightViewProj * vec4(world.xyz + uNormalOffset * normal, 1.0);
    gl_Position = uViewProj * world;
}
)";

const char* const cLitFragment = R"(#version 330 core
in vec3 vWorld;
in vec3 vNormal;
in vec4 vLight;
uniform vec3 uColor;
uniform vec3 uLightDir;
uniform vec3 uEye;
uniform vec3 uUp;
uniform sampler2DShadow uShadowMap;
uniform float uShadowTexel;
uniform int uIsFloor;
uniform vec3 uFloorOrigin;
uniform vec3 uFloorU;
uniform vec3 uFloorV;
uniform float uTile;
uniform vec3 uFadeCentre;
uniform vec2 uFade;
uniform vec3 uBackground;
out vec4 fragColor;

float lit(vec3 p)
{
    if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0)
        return 1.0; // outside the shadow map: nothing casts there
    float reference = min(p.z, 1.0) - 0.0005;
    float sum = 0.0;
    // 2x2 taps half a texel apart, each a bilinear 2x2 comparison: a smooth 3x3-texel penumbra.
    sum += texture(uShadowMap, vec3(p.xy + vec2(-0.5, -0.5) * uShadowTexel, reference));
    sum += texture(uShadowMap, vec3(p.xy + vec2(0.5, -0.5) * uShadowTexel, reference));
    sum += texture(uShadowMap, vec3(p.xy + vec2(-0.5, 0.5) * uShadowTexel, reference));
    sum += texture(uShadowMap, vec3(p.xy + vec2(0.5, 0.5) * uShadowTexel, reference));
    return 0.25 * sum;
}

void main()
{
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing)
        n = -n;
    vec3 base = uColor;
    float specularStrength = 0.22;
    if (uIsFloor == 1)
    {
        vec3 d = vWorld - uFloorOrigin;
        vec2 uv = vec2(dot(d, uFloorU), dot(d, uFloorV)) / uTile;
        // Box-filtered checker: averages the pattern over the pixel footprint (no moire).
        vec2 w = max(fwidth(uv), vec2(1e-4));
        vec2 i = 2.0 * (abs(fract((uv - 0.5 * w) * 0.5) - 0.5) - abs(fract((uv + 0.5 * w) * 0.5) - 0.5)) / w;
        float checker = 0.5 - 0.5 * i.x * i.y;
        base = mix(vec3(0.62, 0.63, 0.65), vec3(0.47, 0.48, 0.50), checker);
        specularStrength = 0.06;
    }
    vec3 l = -uLightDir;
    vec3 v = normalize(uEye - vWorld);
    float diffuse = max(dot(n, l), 0.0);
    float shadow = diffuse > 0.0 ? lit(vLight.xyz / vLight.w * 0.5 + 0.5) : 0.0;
    vec3 h = normalize(l + v);
    float specular = diffuse > 0.0 ? specularStrength * pow(max(dot(n, h), 0.0), 64.0) : 0.0;
    float hemisphere = 0.5 + 0.5 * dot(n, uUp);
    vec3 ambient = base * mix(0.16, 0.34, hemisphere);
    vec3 color = ambient + shadow * (0.95 * diffuse * base + vec3(specular));
    if (uIsFloor == 1)
    {
        vec3 d = vWorld - uFadeCentre;
        float r = length(vec2(dot(d, uFloorU), dot(d, uFloorV)));
        color = mix(color, uBackground, smoothstep(uFade.x, uFade.y, r));
    }
    fragColor = vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)";

const char* const cDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uMvp;
void main()
{
    gl_Position = uMvp * vec4(aPosition, 1.0);
}
)";

const char* const cDepthFragment = R"(#version 330 core
void main()
{
}
)";

GLuint compile(GLenum type, const char* source)
{
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE)
    {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw std::runtime_error("render: shader compilation failed: " + log);
    }
    return shader;
}

GLuint link(const char* vertex, const char* fragment)
{
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex);
    GLuint fs = 0;
    try
    {
        fs = compile(GL_FRAGMENT_SHADER, fragment);
    }
    catch (...)
    {
        glDeleteShader(vs);
        throw;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE)
    {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(length > 0 ? length : 1), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        glDeleteProgram(program);
        throw std::runtime_error("render: shader link failed: " + log);
    }
    return program;
}

} // namespace

LitProgram makeLitProgram()
{
    LitProgram p;
    p.id = link(cLitVertex, cLitFragment);
    const GLuint id = p.id;
    p.model = glGetUniformLocation(id, "uModel");
    p.viewProj = glGetUniformLocation(id, "uViewProj");
    p.lightViewProj = glGetUniformLocation(id, "uLightViewProj");
    p.color = glGetUniformLocation(id, "uColor");
    p.lightDir = glGetUniformLocation(id, "uLightDir");
    p.eye = glGetUniformLocation(id, "uEye");
    p.up = glGetUniformLocation(id, "uUp");
    p.shadowMap = glGetUniformLocation(id, "uShadowMap");
    p.shadowTexel = glGetUniformLocation(id, "uShadowTexel");
    p.normalOffset = glGetUniformLocation(id, "uNormalOffset");
    p.isFloor = glGetUniformLocation(id, "uIsFloor");
    p.floorOrigin = glGetUniformLocation(id, "uFloorOrigin");
    p.floorU = glGetUniformLocation(id, "uFloorU");
    p.floorV = glGetUniformLocation(id, "uFloorV");
    p.tile = glGetUniformLocation(id, "uTile");
    p.fadeCentre = glGetUniformLocation(id, "uFadeCentre");
    p.fade = glGetUniformLocation(id, "uFade");
    p.background = glGetUniformLocation(id, "uBackground");
    return p;
}

DepthProgram makeDepthProgram()
{
    DepthProgram p;
    p.id = link(cDepthVertex, cDepthFragment);
    p.mvp = glGetUniformLocation(p.id, "uMvp");
    return p;
}

void deleteProgram(unsigned id)
{
    if (id != 0)
    {
        glDeleteProgram(id);
    }
}

} // namespace frontier::render
