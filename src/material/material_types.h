// The one list of shaded material types and the one dispatch over it (pbrt-v4's ForEachType over
// Material::Types()): the renderer's shading kernels, IGI's VPL BSDFs and the material descriptions all go
// through these, so adding a type means adding it to the enum and to kShadedMaterialTypes, nothing else here.
#pragma once
#include <tuple>
#include <type_traits>
#include <utility>

#include "material/material.h"

namespace torte {

/// A compile-time list of material types.
template <MaterialType... Ts>
struct MaterialTypeList {
  static constexpr int size = int(sizeof...(Ts));
};

/// Every type with a shading kernel, in enum order (Mix and Bump are resolved before shading).
using ShadedMaterialTypes =
    MaterialTypeList<MaterialType::Lambert, MaterialType::OrenNayar, MaterialType::Mirror, MaterialType::Conductor,
                     MaterialType::Dielectric, MaterialType::ThinDielectric, MaterialType::CoatedDiffuse>;
static_assert(ShadedMaterialTypes::size == kShadedMaterialTypeCount, "every shaded MaterialType is in the list");

/// The type T as a value a generic lambda can take: `[&](auto t) { constexpr MaterialType T = t; ... }`.
template <MaterialType T>
using MaterialTypeTag = std::integral_constant<MaterialType, T>;

namespace detail {
template <MaterialType... Ts>
constexpr bool list_in_enum_order(MaterialTypeList<Ts...>) {
  int i = 0;
  return ((int(Ts) == i++) && ...);
}
static_assert(list_in_enum_order(ShadedMaterialTypes{}), "std::get<int(T)> on per-type tuples relies on it");

template <class Fn, MaterialType... Ts>
constexpr void for_each_type(MaterialTypeList<Ts...>, Fn&& fn) {
  (fn(MaterialTypeTag<Ts>{}), ...);
}
template <class Fn, MaterialType... Ts>
constexpr bool dispatch_type(MaterialTypeList<Ts...>, MaterialType t, Fn&& fn) {
  return ((t == Ts && (fn(MaterialTypeTag<Ts>{}), true)) || ...);
}
template <template <MaterialType> class F, MaterialType... Ts>
auto per_type_tuple(MaterialTypeList<Ts...>) -> std::tuple<F<Ts>...>;
}  // namespace detail

/// Calls fn(MaterialTypeTag<T>{}) for every shaded type T, in enum order (compile-time unrolled).
template <class Fn>
constexpr void for_each_shaded_type(Fn&& fn) {
  detail::for_each_type(ShadedMaterialTypes{}, fn);
}

/// Calls fn(MaterialTypeTag<T>{}) for the shaded type T == t, once per call site (a compare chain the compiler
/// turns into a switch, no virtual call). Returns false, calling nothing, when t is not shaded.
template <class Fn>
constexpr bool dispatch_shaded(MaterialType t, Fn&& fn) {
  return detail::dispatch_type(ShadedMaterialTypes{}, t, fn);
}

/// std::tuple<F<T>...> over the shaded types; element int(T) belongs to type T.
template <template <MaterialType> class F>
using PerShadedType = decltype(detail::per_type_tuple<F>(ShadedMaterialTypes{}));

}  // namespace torte
