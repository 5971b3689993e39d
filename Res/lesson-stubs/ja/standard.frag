#version 450

layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;
layout(location=2) in vec3 inNormal;
layout(location=3) in vec3 inShadowTexcoord;

layout(binding=2) uniform sampler2DShadow texShadow;

layout(location=100) uniform vec4 objectColor;
layout(location=101) uniform vec3 lightDirection; // 面からライトへ向かう向き
layout(location=102) uniform vec3 lightColor;
layout(location=103) uniform vec3 ambientColor;
layout(location=104) uniform int shadowEnabled;

// AOは環境光の項だけに掛けます(深度のプリパスの後): 遮蔽率は1/2サイズです。
layout(binding=3) uniform sampler2D texAO;
layout(location=105) uniform int aoAmbientOnly;
layout(location=106) uniform vec2 invScreenSize;
layout(location=107) uniform float aoPower;

out vec4 outColor;

float Shadow(vec3 normal)
{
  if (shadowEnabled == 0) {
    return 1.0;
  }
  vec3 st = inShadowTexcoord;
  // ライトの箱の外: 照らされています。
  if (any(lessThan(st, vec3(0))) || any(greaterThan(st, vec3(1)))) {
    return 1.0;
  }
  // ハードウェアの2×2の比較を3×3回行うPCF: アクネのないやわらかな影の縁。
  vec2 texel = 1.0 / vec2(textureSize(texShadow, 0));
  float sum = 0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      sum += texture(texShadow, vec3(st.xy + vec2(x, y) * texel, st.z - 0.0015));
    }
  }
  return sum / 9.0;
}

void main()
{
  vec3 n = inNormal;
  float len2 = dot(n, n);
  // normalize(0)を防ぎます(メッシュの法線が縮退している場合)。
  n = len2 > 1e-12 ? n * inversesqrt(len2) : vec3(0, 1, 0);
  if (!gl_FrontFacing) {
    n = -n;
  }
  float diffuse = max(dot(n, normalize(lightDirection)), 0.0) * Shadow(n);
  // 半球の環境光: 地面からより空からのほうが少し明るくします。
  vec3 ambient = ambientColor * (0.75 + 0.25 * n.y);
  if (aoAmbientOnly != 0) {
    float visibility = clamp(1.0 - texture(texAO, gl_FragCoord.xy * invScreenSize).x, 0.0, 1.0);
    ambient *= pow(visibility, aoPower);
  }
  outColor = vec4(objectColor.rgb * (ambient + lightColor * diffuse), objectColor.a);
}
