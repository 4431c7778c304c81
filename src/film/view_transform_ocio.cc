// View transforms for display outputs (view_transform.h), in the image module: standard and filmic are
// OpenColorIO processors built from OCIO's built-in transforms (no config file to find or ship); AgX is not in
// OCIO 2.1 (Debian 12), whose configs carry it only as a baked LUT, so its published analytic fit is evaluated here.
#include "film/view_transform.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/error.h"

namespace torte {

namespace OCIO = OCIO_NAMESPACE;

namespace {

OCIO::TransformRcPtr builtin(const char* style, OCIO::TransformDirection dir = OCIO::TRANSFORM_DIR_FORWARD) {
  OCIO::BuiltinTransformRcPtr t = OCIO::BuiltinTransform::Create();
  t->setStyle(style);
  t->setDirection(dir);
  return t;
}

OCIO::ConstCPUProcessorRcPtr make_processor(ViewTransform view) {
  OCIO::GroupTransformRcPtr group = OCIO::GroupTransform::Create();
  if (view == ViewTransform::Standard) {
    // The sRGB curve itself (IEC 61966-2-1: gamma 2.4, offset 0.055, linear below), inverted to encode. Going
    // through XYZ and OCIO's sRGB display instead differs by a matrix round trip, up to 2e-4: a step of 8 bits.
    OCIO::ExponentWithLinearTransformRcPtr srgb = OCIO::ExponentWithLinearTransform::Create();
    srgb->setGamma({2.4, 2.4, 2.4, 1});
    srgb->setOffset({0.055, 0.055, 0.055, 0});
    srgb->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
    group->appendTransform(srgb);
  } else {
    // ACES 1.0 SDR video on an sRGB display, as the ACES OCIO configs chain it: scene-linear Rec.709 to
    // ACEScg (AP1), to ACES2065-1 (AP0), through the reference rendering and output transform to display XYZ.
    group->appendTransform(builtin("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD", OCIO::TRANSFORM_DIR_INVERSE));
    group->appendTransform(builtin("ACEScg_to_ACES2065-1"));
    group->appendTransform(builtin("ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0"));
    group->appendTransform(builtin("DISPLAY - CIE-XYZ-D65_to_sRGB"));
  }
  OCIO::ConstConfigRcPtr config = OCIO::Config::CreateRaw();
  return config->getProcessor(group)->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                               OCIO::OPTIMIZATION_LOSSLESS);
}

const OCIO::ConstCPUProcessorRcPtr& processor(ViewTransform view) {
  static std::once_flag once[2];
  static OCIO::ConstCPUProcessorRcPtr procs[2];
  const int i = view == ViewTransform::Standard ? 0 : 1;
  std::call_once(once[i], [&] {
    try {
      procs[i] = make_processor(view);
    } catch (const OCIO::Exception& e) {
      throw Error(std::string("OpenColorIO cannot build the ") + view_transform_name(view) + " view: " + e.what());
    }
  });
  return procs[i];
}

// AgX's base rendering as published by Sobotka (2022) in its minimal analytic form (B. Wrensch, "Minimal AgX
// implementation", 2023): inset matrix, log2 over [-12.47393, 4.026069] stops, a 6th-order sigmoid fit of the
// base contrast LUT, outset matrix. The result is display-encoded (sRGB-like 2.2 display), ready for 8 bits.
void agx(float* rgb) {
  constexpr float kInset[3][3] = {{0.842479062253094f, 0.0784335999999992f, 0.0792237451477643f},
                                  {0.0423282422610123f, 0.878468636469772f, 0.0791661274605434f},
                                  {0.0423756549057051f, 0.0784336f, 0.879142973793104f}};
  constexpr float kOutset[3][3] = {{1.19687900512017f, -0.0980208811401368f, -0.0990297440797205f},
                                   {-0.0528968517574562f, 1.15190312990417f, -0.0989611768448433f},
                                   {-0.0529716355144438f, -0.0980434501171241f, 1.15107367264116f}};
  constexpr float kMinEv = -12.47393f, kMaxEv = 4.026069f;
  float v[3];
  for (int r = 0; r < 3; ++r) {
    const float x = kInset[r][0] * rgb[0] + kInset[r][1] * rgb[1] + kInset[r][2] * rgb[2];
    // log2 of 0 (or less) is below the range: the darkest code, as a clamp of -inf would give.
    const float ev = x > 0 ? std::clamp(std::log2(x), kMinEv, kMaxEv) : kMinEv;
    const float t = (ev - kMinEv) / (kMaxEv - kMinEv);
    const float t2 = t * t, t4 = t2 * t2;
    v[r] = 15.5f * t4 * t2 - 40.14f * t4 * t + 31.96f * t4 - 6.868f * t2 * t + 0.4298f * t2 + 0.1191f * t - 0.00232f;
  }
  for (int r = 0; r < 3; ++r) rgb[r] = kOutset[r][0] * v[0] + kOutset[r][1] * v[1] + kOutset[r][2] * v[2];
}

}  // namespace

void apply_view_transform(ViewTransform view, float exposure, const Image& image, std::vector<float>& out) {
  const size_t n = image.pixels.size();
  out.resize(3 * n);
  const float scale = std::exp2(exposure);
  for (size_t i = 0; i < n; ++i) {
    // A pixel with any non-finite channel is a failed estimate; showing it black is the least misleading.
    const Rgb p = image.pixels[i].is_finite() ? image.pixels[i] * scale : Rgb(0);
    out[3 * i] = p.r, out[3 * i + 1] = p.g, out[3 * i + 2] = p.b;
  }
  if (view == ViewTransform::Agx) {
    for (size_t i = 0; i < n; ++i) agx(&out[3 * i]);
  } else if (n > 0) {
    // Negative light (a filter's ringing) has no display value; the ACES rendering would map it to a colour.
    for (float& v : out) v = std::max(v, 0.0f);
    OCIO::PackedImageDesc desc(out.data(), long(n), 1, 3);
    processor(view)->apply(desc);
  }
  for (float& v : out) v = v > 0 ? std::min(v, 1.0f) : 0.0f;  // also a NaN a transform made
}

}  // namespace torte
