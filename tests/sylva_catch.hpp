#pragma once
// Includes Catch2 whichever major version is installed (Debian ships 2.13; 3.x works too).
#if defined(SYLVA_CATCH_V3)
#include <catch2/catch_all.hpp>
#else
#include <catch2/catch.hpp>
#endif
