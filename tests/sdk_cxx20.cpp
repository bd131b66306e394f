// The public SDK headers compile as C++20 (a third party's C++ plugin includes them): the build
// fails here if a header uses a C++ keyword as a name (ABI 1.5 renamed `requires`).
#include <shadelab/shadelab.h>
#include <shadelab/harness.h>
#include <shadelab/ext/shadow_maps.h>
#include <shadelab/ext/environment.h>
#include <shadelab/input.h>
#include <shadelab/matrix.h>
int main() {
    sl_plugin_desc d{};
    d.dependencies = nullptr;
    return (int)d.abi_major;
}
