#ifdef __cplusplus
}  // namespace aor::shader
#endif
