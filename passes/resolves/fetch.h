#pragma once
// `fetch`: the shader resolve of an EQAA surface through the texture unit's fetch path
// (hw-facts §1.4): per pixel one FMASK read, then one fragment fetch per sample, the mean of the
// fetched colours. An UNKNOWN sample reads fragment 0 (Mesa's 3-bit index), which is what a
// resolve shader unaware of UNKNOWN gets; the box resolve drops such samples instead. It reads
// surfaces with 1 < F < S: with F = 1 it equals the box resolve by definition.
//
//   resolve/fetch   full-screen PS   in: FMASK (ElementBits/8 B), fragments (RGBA8 per slot)
//                                    out: colour (RGBA, modelled RGBA8)
// The kernel is sim::FetchResolvePixel (sim/eqaa_resolve.h), shared with nothing else.

#include <memory>

#include "passes/resolve.h"

namespace passes::resolves {

const ResolveInfo& FetchInfo();
std::unique_ptr<Resolve> MakeFetch(const ResolveContext& context);

}  // namespace passes::resolves
