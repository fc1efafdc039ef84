/* Links the installed libtressvk from C: version check and device requirements (no GPU needed). */
#include <tressvk/tressvk.h>

#include <stdio.h>

int main(void) {
  TvkDeviceRequirements req;
  if (TVK_CHECK_VERSION() != TVK_SUCCESS) {
    fprintf(stderr, "consumer (C): header %d does not match library %u\n", TVK_VERSION_NUM, tressvk_version());
    return 1;
  }
  tressvk_get_device_requirements(&req);
  if (req.min_api_version < VK_API_VERSION_1_3 || !req.synchronization2 || !req.dynamic_rendering) {
    fprintf(stderr, "consumer (C): unexpected device requirements\n");
    return 1;
  }
  {
    /* The default initialisers compile as C and give a valid still frame. */
    TvkSimFrame frame = TVK_SIM_FRAME_DEFAULT_INIT;
    TvkSimParams params = TVK_SIM_PARAMS_DEFAULT_INIT;
    TvkSimSettings settings = TVK_SIM_SETTINGS_DEFAULT_INIT;
    if (frame.dt != 0.0f || frame.transform.rotation[3] != 1.0 || frame.bones || frame.capsule_count != 0u ||
        frame.wind.strength != 0.0f || params.local_iterations != TVK_ITERATIONS_BY_MODEL ||
        settings.time.step_rate != TVK_STEP_RATE_BY_MODEL) {
      fprintf(stderr, "consumer (C): unexpected default initialisers\n");
      return 1;
    }
  }
  printf("consumer (C): TressVK %u, needs Vulkan %u.%u with %u extension(s)\n", tressvk_version(),
         VK_API_VERSION_MAJOR(req.min_api_version), VK_API_VERSION_MINOR(req.min_api_version), req.extension_count);
  return 0;
}
