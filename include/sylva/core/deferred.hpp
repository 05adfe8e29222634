#pragma once
/// @file
/// `detail::Deferred<T, Tag>`: the type `T`, spelled so that it depends on a template
/// parameter `Tag`.
///
/// Why: clang type-checks the non-dependent expressions of a template where the template is
/// defined, not where it is used. Every Eigen expression such a body names (a product, a
/// block, a transpose) is then instantiated in each translation unit that includes the header,
/// whether the program calls the function or not: most of what including the filter and the
/// planar models cost (docs/build-time.md). A body whose variables have a `Deferred` type is
/// dependent, and is compiled only where the template is instantiated.
///
/// Used two ways:
/// - in a class template, member and local types named through `Deferred<T, SomeParameter>`;
/// - in a function template, a parameter `const Deferred<T, Tag>&` with `template <typename Tag
///   = void>`: `Tag` cannot be deduced from it (it is a nested name), so it keeps its default and
///   a caller passes a `T` (or anything that converts to one) as before.

namespace sylva::detail {

template <typename T, typename Tag>
struct DeferredType {
  using type = T;
};

template <typename T, typename Tag>
using Deferred = typename DeferredType<T, Tag>::type;

}  // namespace sylva::detail
