// Helpers of sao.frag (included): view position, per-pixel hash, one sample's obscurance.
// They use sao.frag's uniforms, declared before the #include line.

vec3 ViewPos(vec2 uv, float z)
{
  return vec3((uv * 2.0 - 1.0) * ndcToView * z, -z);
}

float Hash(ivec2 p)
{
  uint h = uint(p.x) * 1664525u + uint(p.y) * 1013904223u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  return float(h & 0xffffu) / 65536.0;
}

float SampleAO(vec3 p, vec3 n, vec2 uv, float lod)
{
  float z = textureLod(texDepth, uv, lod).r;
  vec3 v = ViewPos(uv, z) - p;
  float vv = dot(v, v);
  float f = max(saoInfo.x - vv, 0.0);
  return f * f * f * max((dot(v, n) - saoInfo.z) / (vv + 0.001), 0.0);
}

