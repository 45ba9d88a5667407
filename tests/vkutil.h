/* tests/vkutil.h - what tests/test_vulkan.c and fuzz/fuzz_vulkan.c read back
   from the device beyond the public downloads.  Include it after
   manylods_vk.h with its implementation (it uses the private download). */
#ifndef MANYLODS_TEST_VKUTIL_H
#define MANYLODS_TEST_VKUTIL_H

#include <string.h>

/* The device views buffer of a cut (mlodvk_cut_get_buffers().views),
   downloaded into bytes (8 * MLOD_IF_VIEW_STRIDE per view). */
static mlod_result vk_download_views(mlodvk_context *context, mlodvk_cut *cut, uint32_t view_count, unsigned char *bytes,
                                     mlod_error *error)
{
    mlodvk__buffer src;
    mlodvk__download_range range;
    memset(&src, 0, sizeof src);
    src.buffer = mlodvk_cut_get_buffers(cut).views;
    range.src = &src;
    range.size = 8 * MLOD_IF_VIEW_STRIDE * (VkDeviceSize)view_count;
    range.dst = bytes;
    return mlodvk__download(context, &range, 1, error);
}

#endif
