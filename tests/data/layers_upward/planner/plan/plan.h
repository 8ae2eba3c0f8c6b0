#pragma once
// The header the upward include names (tests/CMakeLists.txt, layer_check_refuses_an_upward_include).
