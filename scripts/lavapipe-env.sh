# Sourced by the scripts: select Mesa's lavapipe ICD (named lvp_icd.x86_64.json in Mesa 22, lvp_icd.json in
# Mesa 25) unless the caller already chose a driver.
if [ -z "${VK_DRIVER_FILES:-}" ]; then
  _icd=$(ls /usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -1 || true)
  if [ -n "$_icd" ]; then export VK_DRIVER_FILES="$_icd" VK_ICD_FILENAMES="$_icd"; fi
  unset _icd
fi
