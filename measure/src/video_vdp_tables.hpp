// ColorVideoVDP's published data (video_vdp.hpp), defined in video_vdp_tables.cpp, which
// scripts/video_vdp_tables.py writes from a ColorVideoVDP checkout.
#pragma once

namespace saagen::measure::video_vdp_data {

// cvvdp_parameters.json: the keys the model reads (video_vdp.hpp names the step of each).
struct VideoVdpParameters {
  double mask_p, mask_c, pu_dilate, beta, beta_t, beta_tch, beta_sch, sensitivity_correction, jod_a, jod_exp, ch_chrom_w, ch_trans_w, d_max,
      image_int;
  double mask_q[4];  // per channel: sustained achromatic, red-green, yellow-violet, transient achromatic
  double sigma_tf[4], beta_tf[4];
  double xcm_weights[16];  // log2 of the cross-channel masking weights, [masker * 4 + masked]
  double baseband_weight[4];
};
extern const VideoVdpParameters kParameters;

// display_models.json's standard_fhd.
struct DisplayData {
  int resolution_width, resolution_height;
  double viewing_distance_meters, diagonal_size_inches, max_luminance, contrast, e_ambient, k_refl;
};
extern const DisplayData kStandardFhd;

// color_spaces.json: linear RGB -> CIE XYZ of the display's colour space (rows X, Y, Z).
extern const double kRgbToXyz[3][3];

// The castleCSF table: background luminances, spatial frequencies, and log10 sensitivity
// [channel][luminance][frequency] (channels: sustained achromatic, red-green, yellow-violet at
// 0 Hz; transient achromatic at 5 Hz).
inline constexpr int kCsfLuminances = 32, kCsfFrequencies = 32;
extern const double kCsfLuminance[kCsfLuminances];
extern const double kCsfRho[kCsfFrequencies];
extern const double kCsfLogSensitivity[4][kCsfLuminances][kCsfFrequencies];

}  // namespace saagen::measure::video_vdp_data
