# Sourced by the scripts that change packages (deps.sh, test-without-osmesa.sh).
# as_root_prefix: sets the array `sudo` to what runs a command as root:
# nothing when root, `sudo -n` when sudo works without a password; fails
# when neither.
as_root_prefix() {
  if [ "$(id -u)" -eq 0 ]; then
    sudo=()
  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    sudo=(sudo -n)
  else
    return 1
  fi
}
