// hls/sectoral_ism.hpp as an HLS tool sees it (__SYNTHESIS__ defined, the HLS pragmas
// expanded), instantiated for both configurations: it must compile cleanly.
#include <cstdint>

#include "hls/sectoral_ism.hpp"
#include "sectoral_ism_cone12_config.hpp"
#include "sectoral_ism_cone16_config.hpp"

namespace intgrid::hls {

template void sectoral_ism_kernel<hw::SectoralIsmCone16>(
    std::uint32_t, std::int16_t (&)[hw::SectoralIsmCone16::rings * hw::SectoralIsmCone16::bins]);
template void sectoral_ism_kernel<hw::SectoralIsmCone12>(
    std::uint32_t, std::int16_t (&)[hw::SectoralIsmCone12::rings * hw::SectoralIsmCone12::bins]);

}  // namespace intgrid::hls
