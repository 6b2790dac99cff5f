// Parameters of sectoral_ism, configuration cone16: sectoral_ism #(`SECTORAL_ISM_CONE16_PARAMS) u (...);
`define SECTORAL_ISM_CONE16_PARAMS \
  .READING_W(16), \
  .RINGS(40), \
  .BINS(16), \
  .SECTORS(4), \
  .CLASSES(6), \
  .WINDOW(13), \
  .IDX_W(8), \
  .READING_FRAC(8), \
  .LOG_FRAC(8), \
  .QUAD_SHIFT(24), \
  .LOG_W(20), \
  .COEF_W(19), \
  .NORM_W(12), \
  .WEIGHT_W(13), \
  .PHI_N(2440), \
  .PHI_W(8), \
  .THR_W(14), \
  .BUCKET_SHIFT(6), \
  .BUCKET_N(148), \
  .QUAD_COEF_FILE("config/cone16/sectoral_ism_cone16_quad_coef.mem"), \
  .LOG_NORM_FILE("config/cone16/sectoral_ism_cone16_log_norm.mem"), \
  .LOG_WEIGHT_FILE("config/cone16/sectoral_ism_cone16_log_weight.mem"), \
  .LOG_ADD_FILE("config/cone16/sectoral_ism_cone16_log_add.mem"), \
  .THRESHOLDS_FILE("config/cone16/sectoral_ism_cone16_thresholds.mem"), \
  .THRESHOLD_BUCKET_FILE("config/cone16/sectoral_ism_cone16_threshold_bucket.mem")
