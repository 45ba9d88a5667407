/* tests/compile/vulkan_unit.c - manylods_vk.h with VK_NO_PROTOTYPES: the
   header must never need a Vulkan prototype, so that it works next to volk
   and other loaders.  Built by tests/compile/vulkan.sh as C and as C++; it
   links without the Vulkan loader and only checks that the API is there. */
#define VK_NO_PROTOTYPES
#include <vulkan/vulkan.h>
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../../manylods_vk.h"
#include <stdio.h>

int main(void)
{
    mlodvk_context_desc desc;
    mlodvk_context *context = NULL;
    mlod_error error;
    memset(&desc, 0, sizeof desc);
    /* no instance: refused with a message, nothing created */
    if (mlodvk_context_create(&desc, &context, &error) != MLOD_ERROR_INVALID_ARGUMENT || context) return 1;
    printf("%s\n", error.message);
    return 0;
}
