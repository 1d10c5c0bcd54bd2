# Written by bench/tradeoff (tradeoff --plot-only rewrites it from tradeoff.csv).
# Run in this directory: gnuplot tradeoff.gp
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { term = 'pngcairo' } else { term = 'png' }
$all_0 << EOD
0.007761 0.0526401
0.03394 0.0219962
0.4575 0.0244749
0.015 0.178404
0.07886 0.134232
0.5736 0.123968
0.0471 0.0630069
0.2911 0.0161993
1.212 0.010472
0.05867 0.0571288
0.2021 0.0135638
1.273 0.00389021
0.07143 1.03552
0.2118 0.0979018
1.223 0.0180732
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
0.2123 0.368073
0.6072 0.0651633
3.238 0.0146724
0.001935 0.177435
0.009514 0.177474
0.0523 0.176023
0.2087 0.174937
0.002837 0.136163
0.01229 0.132972
0.07104 0.131363
0.4337 0.130298
0.008269 0.147234
0.03473 0.0554027
0.00484 0.0596597
0.02127 0.0543234
0.1077 0.0528011
0.7702 0.0522031
0.01197 0.13007
0.05252 0.123857
0.3424 0.121462
1.951 0.120138
0.134 0.112953
0.5187 0.0251173
0.01248 0.0460995
0.0837 0.0105921
0.2965 0.00257184
1.888 0.00063574
0.02151 0.136182
0.08071 0.0295334
0.3271 0.00705136
2.569 0.00173293
0.2851 0.596417
0.6685 0.0989017
0.007183 0.0670127
0.03925 0.0143063
0.1393 0.00340344
0.7973 0.000835503
0.04586 0.261251
0.06457 0.042566
0.2996 0.00953545
1.997 0.00229907
0.1758 5.58737
0.5016 0.24322
0.1031 0.246481
0.2142 0.0490536
1.148 0.0114218
0.1019 0.197164
0.3458 0.0409418
1.291 0.00963905
0.07058 0.154906
0.4247 0.0325253
0.9298 0.00769165
0.07503 0.0932408
0.204 0.0209143
0.8916 0.00503757
0.07143 0.144951
0.1992 0.031174
1.057 0.00741586
0.0075 0.0526401
0.03323 0.0219962
0.2144 0.0244749
0.03917 0.0630069
0.1344 0.0161993
0.9841 0.010472
0.01235 0.290748
0.03825 0.0558499
0.148 0.0128874
0.1013 0.290749
0.267 0.0558505
1.159 0.0128881
0.012 0.290748
0.03674 0.0558499
0.1591 0.0128887
0.004943 0.0460989
0.01867 0.0105915
0.1218 0.00257255
0.9201 0.000634954
0.01026 0.0460995
0.05826 0.0105921
0.1894 0.00257184
1.885 0.000635739
0.006727 0.0460989
0.02261 0.0105927
0.1542 0.00257121
1.639 0.000636544
0.1453 0.290749
0.4724 0.0558505
1.744 0.0128881
0.2453 0.290749
0.934 0.0558509
4.129 0.0128885
0.00909 0.0526411
0.03238 0.0219926
0.1322 0.0244775
EOD
$front_0 << EOD
0.004943 0.0460989 "corr-silling"
0.006727 0.0460989 "corr-silling"
0.01867 0.0105915 "corr-silling"
0.1218 0.00257255 "corr-silling"
0.1542 0.00257121 "corr-silling"
0.7973 0.000835503 "corr-none"
0.9201 0.000634954 "corr-silling"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'mms.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'mms: manufactured static field (L2 error of u)'
set title 'sweep: model'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.007761 0.0526401
0.03394 0.0219962
0.4575 0.0244749
e
0.015 0.178404
0.07886 0.134232
0.5736 0.123968
e
0.0471 0.0630069
0.2911 0.0161993
1.212 0.010472
e
0.05867 0.0571288
0.2021 0.0135638
1.273 0.00389021
e
0.07143 1.03552
0.2118 0.0979018
1.223 0.0180732
e
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
e
0.2123 0.368073
0.6072 0.0651633
3.238 0.0146724
e
set title 'sweep: m'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.001935 0.177435
0.009514 0.177474
0.0523 0.176023
0.2087 0.174937
e
0.002837 0.136163
0.01229 0.132972
0.07104 0.131363
0.4337 0.130298
e
0.008269 0.147234
0.03473 0.0554027
e
0.00484 0.0596597
0.02127 0.0543234
0.1077 0.0528011
0.7702 0.0522031
e
0.01197 0.13007
0.05252 0.123857
0.3424 0.121462
1.951 0.120138
e
0.134 0.112953
0.5187 0.0251173
e
0.01248 0.0460995
0.0837 0.0105921
0.2965 0.00257184
1.888 0.00063574
e
0.02151 0.136182
0.08071 0.0295334
0.3271 0.00705136
2.569 0.00173293
e
0.2851 0.596417
0.6685 0.0989017
e
0.007183 0.0670127
0.03925 0.0143063
0.1393 0.00340344
0.7973 0.000835503
e
0.04586 0.261251
0.06457 0.042566
0.2996 0.00953545
1.997 0.00229907
e
0.1758 5.58737
0.5016 0.24322
e
set title 'sweep: influence'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
e
0.1031 0.246481
0.2142 0.0490536
1.148 0.0114218
e
0.1019 0.197164
0.3458 0.0409418
1.291 0.00963905
e
0.07058 0.154906
0.4247 0.0325253
0.9298 0.00769165
e
0.07503 0.0932408
0.204 0.0209143
0.8916 0.00503757
e
0.07143 0.144951
0.1992 0.031174
1.057 0.00741586
e
set title 'sweep: precision'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 adr double', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 3.015 adr float', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-silling m 1.5 adr double', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-silling m 1.5 float', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-silling m 1.5 adr float'
0.007761 0.0526401
0.03394 0.0219962
0.4575 0.0244749
e
0.0471 0.0630069
0.2911 0.0161993
1.212 0.010472
e
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
e
0.01248 0.0460995
0.0837 0.0105921
0.2965 0.00257184
1.888 0.00063574
e
0.0075 0.0526401
0.03323 0.0219962
0.2144 0.0244749
e
0.03917 0.0630069
0.1344 0.0161993
0.9841 0.010472
e
0.01235 0.290748
0.03825 0.0558499
0.148 0.0128874
e
0.1013 0.290749
0.267 0.0558505
1.159 0.0128881
e
0.012 0.290748
0.03674 0.0558499
0.1591 0.0128887
e
0.004943 0.0460989
0.01867 0.0105915
0.1218 0.00257255
0.9201 0.000634954
e
0.01026 0.0460995
0.05826 0.0105921
0.1894 0.00257184
1.885 0.000635739
e
0.006727 0.0460989
0.02261 0.0105927
0.1542 0.00257121
1.639 0.000636544
e
set title 'sweep: connectivity'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
e
0.1453 0.290749
0.4724 0.0558505
1.744 0.0128881
e
0.2453 0.290749
0.934 0.0558509
4.129 0.0128885
e
set title 'sweep: solver'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.007761 0.0526401
0.03394 0.0219962
0.4575 0.0244749
e
0.1013 0.290749
0.3275 0.0558505
1.191 0.0128881
e
0.01235 0.290748
0.03825 0.0558499
0.148 0.0128874
e
0.00909 0.0526411
0.03238 0.0219926
0.1322 0.0244775
e
unset multiplot
set output
$all_1 << EOD
0.01026 0.0507224
0.05244 0.00819064
0.2839 0.0136069
0.008504 0.241824
0.05198 0.202483
0.7408 0.18231
0.07276 0.0832629
0.3147 0.050905
2.052 0.0341128
0.07039 0.0721965
0.3535 0.0357857
1.293 0.0168654
0.05939 0.525384
0.2412 0.534887
2.125 0.566492
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
0.1492 0.00132589
0.9538 0.00168468
3.144 0.00101277
0.002396 0.252515
0.01102 0.238393
0.06422 0.23109
0.3799 0.227377
0.004329 0.138175
0.02415 0.135877
0.1449 0.134639
1.36 0.133997
0.01057 0.2734
0.06007 0.157715
0.5836 0.0984242
0.009639 0.00568258
0.0384 0.0426014
0.6789 0.0678351
2.001 0.0807372
0.009151 0.217227
0.04919 0.185566
0.4182 0.169125
3.027 0.160748
0.05076 0.0471587
0.2835 0.0325057
2.106 0.0253418
0.009913 0.0751876
0.04903 0.038408
0.2475 0.0194306
1.695 0.00977488
0.01489 0.0742747
0.08035 0.0381068
0.4996 0.0193113
2.93 0.00972214
0.1035 0.0977401
0.5613 0.0515511
3.403 0.026214
0.01344 0.071177
0.03857 0.0364808
0.2017 0.0185076
1.225 0.00931563
0.02342 0.32161
0.08995 0.28303
0.5956 0.266232
3.214 0.258404
0.1066 1.13546
0.6323 1.69532
4.424 1.95389
0.09277 0.0378733
1.133 0.0185499
2.112 0.00926294
0.01269 0.0715705
0.04066 0.0366709
0.7147 0.0185467
2.983 0.00932489
0.09982 0.0715467
0.4714 0.0361211
2.585 0.0182102
0.02919 0.0722435
0.1079 0.0367681
0.1236 0.0652823
0.4623 0.0330262
2.52 0.0166723
0.01407 0.0721246
0.1412 0.0367579
0.4955 0.0185616
2.647 0.00932757
0.06573 0.0837893
0.4313 0.0428115
2.315 0.0216584
0.02584 0.0720388
0.09503 0.0367397
0.5428 0.0185574
2.951 0.00932651
0.1851 0.0812775
0.3522 0.0413515
2.184 0.0208994
0.01505 0.0721226
0.05562 0.0367575
0.7413 0.0185615
2.371 0.00932755
0.01554 0.0511258
0.0707 0.00857885
0.6624 0.0132261
0.1564 0.0827449
0.2006 0.0504176
2.273 0.0336376
0.01635 0.0064447
0.1043 0.00433136
0.3686 0.00234579
0.2429 0.00644517
0.7882 0.00432651
2.541 0.0023388
0.02523 0.00644148
0.08606 0.00432156
0.3542 0.00234598
0.00698 0.0751849
0.04076 0.0384033
0.2945 0.0194375
3.918 0.00978474
0.01823 0.0751876
0.0901 0.038408
1.284 0.0194306
2.715 0.00977488
0.01614 0.0751852
0.03984 0.038404
0.2872 0.0194369
4.693 0.00978361
0.1647 0.00644496
0.3872 0.0043265
1.813 0.00233881
0.1749 0.00644549
0.7856 0.00432679
3.731 0.00233895
0.0124 0.0507186
0.05731 0.00818543
0.2719 0.0136144
EOD
$front_1 << EOD
0.00698 0.0751849 "corr-silling"
0.01269 0.0715705 "corr-none"
0.01344 0.071177 "corr-none"
0.01635 0.0064447 "corr-silling"
0.02523 0.00644148 "corr-silling"
0.08606 0.00432156 "corr-silling"
0.1492 0.00132589 "corr-hourglass"
3.144 0.00101277 "corr-hourglass"
EOD
set terminal term size 1560,1260 noenhanced font ',9'
set output 'vq_uniaxial.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 3,3 title 'vq_uniaxial: V-Q uniaxial compression (top displacement)'
set title 'sweep: model'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.01026 0.0507224
0.05244 0.00819064
0.2839 0.0136069
e
0.008504 0.241824
0.05198 0.202483
0.7408 0.18231
e
0.07276 0.0832629
0.3147 0.050905
2.052 0.0341128
e
0.07039 0.0721965
0.3535 0.0357857
1.293 0.0168654
e
0.05939 0.525384
0.2412 0.534887
2.125 0.566492
e
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
e
0.1492 0.00132589
0.9538 0.00168468
3.144 0.00101277
e
set title 'sweep: m'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.002396 0.252515
0.01102 0.238393
0.06422 0.23109
0.3799 0.227377
e
0.004329 0.138175
0.02415 0.135877
0.1449 0.134639
1.36 0.133997
e
0.01057 0.2734
0.06007 0.157715
0.5836 0.0984242
e
0.009639 0.00568258
0.0384 0.0426014
0.6789 0.0678351
2.001 0.0807372
e
0.009151 0.217227
0.04919 0.185566
0.4182 0.169125
3.027 0.160748
e
0.05076 0.0471587
0.2835 0.0325057
2.106 0.0253418
e
0.009913 0.0751876
0.04903 0.038408
0.2475 0.0194306
1.695 0.00977488
e
0.01489 0.0742747
0.08035 0.0381068
0.4996 0.0193113
2.93 0.00972214
e
0.1035 0.0977401
0.5613 0.0515511
3.403 0.026214
e
0.01344 0.071177
0.03857 0.0364808
0.2017 0.0185076
1.225 0.00931563
e
0.02342 0.32161
0.08995 0.28303
0.5956 0.266232
3.214 0.258404
e
0.1066 1.13546
0.6323 1.69532
4.424 1.95389
e
set title 'sweep: influence'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
e
0.09277 0.0378733
1.133 0.0185499
2.112 0.00926294
e
0.09982 0.0715467
0.4714 0.0361211
2.585 0.0182102
e
0.1236 0.0652823
0.4623 0.0330262
2.52 0.0166723
e
0.06573 0.0837893
0.4313 0.0428115
2.315 0.0216584
e
0.1851 0.0812775
0.3522 0.0413515
2.184 0.0208994
e
set title 'sweep: influence-rf1.5'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.01344 0.071177
0.03857 0.0364808
0.2017 0.0185076
1.225 0.00931563
e
0.01269 0.0715705
0.04066 0.0366709
0.7147 0.0185467
2.983 0.00932489
e
0.02919 0.0722435
0.1079 0.0367681
e
0.01407 0.0721246
0.1412 0.0367579
0.4955 0.0185616
2.647 0.00932757
e
0.02584 0.0720388
0.09503 0.0367397
0.5428 0.0185574
2.951 0.00932651
e
0.01505 0.0721226
0.05562 0.0367575
0.7413 0.0185615
2.371 0.00932755
e
set title 'sweep: precision'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 adr double', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 3.015 adr float', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-silling m 1.5 adr double', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-silling m 1.5 float', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-silling m 1.5 adr float'
0.01026 0.0507224
0.05244 0.00819064
0.2839 0.0136069
e
0.07276 0.0832629
0.3147 0.050905
2.052 0.0341128
e
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
e
0.009913 0.0751876
0.04903 0.038408
0.2475 0.0194306
1.695 0.00977488
e
0.01554 0.0511258
0.0707 0.00857885
0.6624 0.0132261
e
0.1564 0.0827449
0.2006 0.0504176
2.273 0.0336376
e
0.01635 0.0064447
0.1043 0.00433136
0.3686 0.00234579
e
0.2429 0.00644517
0.7882 0.00432651
2.541 0.0023388
e
0.02523 0.00644148
0.08606 0.00432156
0.3542 0.00234598
e
0.00698 0.0751849
0.04076 0.0384033
0.2945 0.0194375
3.918 0.00978474
e
0.01823 0.0751876
0.0901 0.038408
1.284 0.0194306
2.715 0.00977488
e
0.01614 0.0751852
0.03984 0.038404
0.2872 0.0194369
4.693 0.00978361
e
set title 'sweep: connectivity'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
e
0.1647 0.00644496
0.3872 0.0043265
1.813 0.00233881
e
0.1749 0.00644549
0.7856 0.00432679
3.731 0.00233895
e
set title 'sweep: solver'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.01026 0.0507224
0.05244 0.00819064
0.2839 0.0136069
e
0.2381 0.00644496
0.3574 0.0043265
1.732 0.00233881
e
0.01635 0.0064447
0.1043 0.00433136
0.3686 0.00234579
e
0.0124 0.0507186
0.05731 0.00818543
0.2719 0.0136144
e
unset multiplot
set output
$all_2 << EOD
0.01255 0.0745181
0.06963 0.025769
0.3985 0.000734461
0.01048 0.251204
0.06606 0.206294
0.3938 0.183248
0.03216 0.0672679
0.1947 0.0344628
1.491 0.0174871
0.04283 0.072804
0.2098 0.0373563
1.865 0.0189543
0.06359 0.541587
0.3997 0.55146
1.836 0.584148
0.07262 0.00808447
0.2219 0.00456743
1.993 0.00237018
0.1395 0.00185344
0.4799 0.00137971
3.132 0.000765259
0.00248 0.29338
0.01217 0.281062
0.05387 0.274639
0.3996 0.271356
0.003396 0.0352363
0.01828 0.0325047
0.1012 0.0310583
0.6935 0.0303141
0.009244 0.319099
0.0526 0.18725
0.3906 0.119641
0.005769 0.0820064
0.04418 0.0420977
0.1692 0.0213322
1.047 0.0107378
0.03052 0.0781639
0.2227 0.0402866
0.5605 0.0204733
2.626 0.0103208
0.04014 0.0384446
0.4494 0.0191922
1.738 0.00970004
0.008999 0.0750447
0.04313 0.0384022
0.3221 0.019433
1.937 0.00977594
0.016 0.0744236
0.07599 0.0381628
0.6478 0.0193272
3.528 0.00972627
0.1132 0.101232
0.653 0.0518795
2.839 0.0261933
0.08008 0.0363258
0.3677 0.0183265
2.139 0.0092307
0.07249 0.070515
0.4183 0.0359856
2.229 0.0181922
0.07272 0.06458
0.3456 0.0329743
1.697 0.0166761
0.04492 0.0835806
0.2814 0.042791
1.511 0.021657
0.1561 0.0807289
0.4314 0.0412969
2.155 0.0208961
0.02621 0.0749388
0.1419 0.0261678
1.052 0.00112275
0.1501 0.0667582
0.4281 0.0339756
1.635 0.0170081
0.01291 0.0080828
0.07135 0.0045723
0.3308 0.00236316
0.05644 0.00808467
0.2937 0.00456743
1.76 0.00237018
0.0145 0.00808784
0.05694 0.00457246
0.3704 0.0023772
0.008077 0.075043
0.03588 0.0383996
0.258 0.01944
3.8 0.00978581
0.017 0.0750447
0.052 0.0384022
0.212 0.019433
1.835 0.00977594
0.007757 0.075044
0.04952 0.0383979
0.2947 0.0194393
4.5 0.00978462
EOD
$front_2 << EOD
0.005769 0.0820064 "lps"
0.007757 0.075044 "corr-silling"
0.008077 0.075043 "corr-silling"
0.01255 0.0745181 "pmb"
0.01291 0.0080828 "corr-silling"
0.05694 0.00457246 "corr-silling"
0.07135 0.0045723 "corr-silling"
0.1395 0.00185344 "corr-hourglass"
0.3985 0.000734461 "pmb"
EOD
set terminal term size 1040,840 noenhanced font ',9'
set output 'vq_isotropic.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,2 title 'vq_isotropic: V-Q isotropic compression (right-edge displacement)'
set title 'sweep: model'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.01255 0.0745181
0.06963 0.025769
0.3985 0.000734461
e
0.01048 0.251204
0.06606 0.206294
0.3938 0.183248
e
0.03216 0.0672679
0.1947 0.0344628
1.491 0.0174871
e
0.04283 0.072804
0.2098 0.0373563
1.865 0.0189543
e
0.06359 0.541587
0.3997 0.55146
1.836 0.584148
e
0.07262 0.00808447
0.2219 0.00456743
1.993 0.00237018
e
0.1395 0.00185344
0.4799 0.00137971
3.132 0.000765259
e
set title 'sweep: m'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.00248 0.29338
0.01217 0.281062
0.05387 0.274639
0.3996 0.271356
e
0.003396 0.0352363
0.01828 0.0325047
0.1012 0.0310583
0.6935 0.0303141
e
0.009244 0.319099
0.0526 0.18725
0.3906 0.119641
e
0.005769 0.0820064
0.04418 0.0420977
0.1692 0.0213322
1.047 0.0107378
e
0.03052 0.0781639
0.2227 0.0402866
0.5605 0.0204733
2.626 0.0103208
e
0.04014 0.0384446
0.4494 0.0191922
1.738 0.00970004
e
0.008999 0.0750447
0.04313 0.0384022
0.3221 0.019433
1.937 0.00977594
e
0.016 0.0744236
0.07599 0.0381628
0.6478 0.0193272
3.528 0.00972627
e
0.1132 0.101232
0.653 0.0518795
2.839 0.0261933
e
set title 'sweep: influence'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.07262 0.00808447
0.2219 0.00456743
1.993 0.00237018
e
0.08008 0.0363258
0.3677 0.0183265
2.139 0.0092307
e
0.07249 0.070515
0.4183 0.0359856
2.229 0.0181922
e
0.07272 0.06458
0.3456 0.0329743
1.697 0.0166761
e
0.04492 0.0835806
0.2814 0.042791
1.511 0.021657
e
0.1561 0.0807289
0.4314 0.0412969
2.155 0.0208961
e
set title 'sweep: precision'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 adr double', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 3.015 adr float', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-silling m 1.5 adr double', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-silling m 1.5 float', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-silling m 1.5 adr float'
0.01255 0.0745181
0.06963 0.025769
0.3985 0.000734461
e
0.03216 0.0672679
0.1947 0.0344628
1.491 0.0174871
e
0.07262 0.00808447
0.2219 0.00456743
1.993 0.00237018
e
0.008999 0.0750447
0.04313 0.0384022
0.3221 0.019433
1.937 0.00977594
e
0.02621 0.0749388
0.1419 0.0261678
1.052 0.00112275
e
0.1501 0.0667582
0.4281 0.0339756
1.635 0.0170081
e
0.01291 0.0080828
0.07135 0.0045723
0.3308 0.00236316
e
0.05644 0.00808467
0.2937 0.00456743
1.76 0.00237018
e
0.0145 0.00808784
0.05694 0.00457246
0.3704 0.0023772
e
0.008077 0.075043
0.03588 0.0383996
0.258 0.01944
3.8 0.00978581
e
0.017 0.0750447
0.052 0.0384022
0.212 0.019433
1.835 0.00977594
e
0.007757 0.075044
0.04952 0.0383979
0.2947 0.0194393
4.5 0.00978462
e
unset multiplot
set output
$all_3 << EOD
0.006462 0.0966072
0.03842 0.0531654
0.2431 0.0315884
0.00654 0.236483
0.03712 0.195019
0.2858 0.174474
0.02399 0.0248073
0.126 0.00470698
1.564 0.019898
0.07849 0.0675591
0.1418 0.0371671
0.873 0.0213948
0.04145 0.750117
0.1917 0.704929
1.362 0.697433
0.04558 0.0381945
0.2157 0.0220039
1.632 0.0116292
0.1252 0.0535838
0.5707 0.0302717
4.659 0.0158957
0.006945 0.380077
0.01994 0.377917
0.07952 0.376641
0.2814 0.375949
0.003176 0.50843
0.01799 0.510967
0.1041 0.512607
1.854 0.513532
0.01632 0.285843
0.147 0.188191
0.6268 0.13995
0.005853 0.19554
0.03102 0.171888
0.4512 0.159429
1.063 0.153008
0.02344 0.460649
0.1341 0.50993
0.5551 0.535074
2.46 0.547806
0.04584 0.0104132
0.383 0.0137034
2.328 0.0259669
0.01638 0.0685613
0.06709 0.0346713
0.2323 0.0174672
1.841 0.00877049
0.01537 0.075287
0.07541 0.0382263
0.433 0.0192779
4.443 0.00968296
0.1039 0.179296
0.4762 0.097721
3.613 0.050799
0.01168 0.0605786
0.1381 0.0301953
0.3859 0.0151451
1.572 0.00757736
0.02221 0.267956
0.3562 0.258753
2.143 0.259484
6.445 0.243291
0.1038 1.55055
0.4252 1.77841
2.553 1.69774
0.07162 0.024992
0.2339 0.011381
1.842 0.00549853
0.01988 0.0601528
0.08212 0.0301825
0.4148 0.015124
2.332 0.00757202
0.06805 0.0701639
0.3354 0.0352164
1.703 0.0176897
0.01023 0.0598209
0.03749 0.0300272
0.05737 0.06402
0.3611 0.0321181
1.84 0.016143
0.009424 0.060652
0.2733 0.0303153
1.614 0.0151651
2.989 0.00758382
0.06862 0.0841219
0.3068 0.0426694
1.507 0.0215079
0.01793 0.061316
0.04044 0.0305339
0.284 0.0152305
2.126 0.00760227
0.07382 0.0829429
0.3932 0.0419844
1.867 0.0211519
0.008704 0.0606604
0.04886 0.0303182
0.3432 0.015166
1.791 0.00758407
0.006926 0.0966072
0.0479 0.0531653
0.5482 0.0315884
0.0358 0.0248073
0.1148 0.00470698
1.268 0.019898
0.01031 0.0381894
0.06152 0.0219968
0.4045 0.0116189
0.05265 0.0381945
0.2465 0.022004
1.315 0.0116292
0.01019 0.0381894
0.06161 0.0219968
0.4427 0.0116189
0.01216 0.068566
0.06047 0.0346782
0.387 0.0174772
4.855 0.00878461
0.01137 0.0685613
0.05306 0.0346713
0.2805 0.0174672
1.227 0.00877049
0.008866 0.068566
0.0506 0.0346781
0.3747 0.0174765
3.982 0.00878087
0.2616 0.0381945
0.2224 0.0220039
1.642 0.0116292
0.09875 0.0381945
0.8346 0.0220039
2.193 0.0116292
EOD
$front_3 << EOD
0.006462 0.0966072 "pmb"
0.008704 0.0606604 "corr-none"
0.009424 0.060652 "corr-none"
0.01019 0.0381894 "corr-silling"
0.03749 0.0300272 "corr-none"
0.06152 0.0219968 "corr-silling"
0.06161 0.0219968 "corr-silling"
0.2323 0.0174672 "corr-silling"
0.2339 0.011381 "corr-silling"
1.227 0.00877049 "corr-silling"
1.572 0.00757736 "corr-none"
1.842 0.00549853 "corr-silling"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'vq_shear.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'vq_shear: V-Q simple shear (top displacement)'
set title 'sweep: model'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.006462 0.0966072
0.03842 0.0531654
0.2431 0.0315884
e
0.00654 0.236483
0.03712 0.195019
0.2858 0.174474
e
0.02399 0.0248073
0.126 0.00470698
1.564 0.019898
e
0.07849 0.0675591
0.1418 0.0371671
0.873 0.0213948
e
0.04145 0.750117
0.1917 0.704929
1.362 0.697433
e
0.04558 0.0381945
0.2157 0.0220039
1.632 0.0116292
e
0.1252 0.0535838
0.5707 0.0302717
4.659 0.0158957
e
set title 'sweep: m'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.006945 0.380077
0.01994 0.377917
0.07952 0.376641
0.2814 0.375949
e
0.003176 0.50843
0.01799 0.510967
0.1041 0.512607
1.854 0.513532
e
0.01632 0.285843
0.147 0.188191
0.6268 0.13995
e
0.005853 0.19554
0.03102 0.171888
0.4512 0.159429
1.063 0.153008
e
0.02344 0.460649
0.1341 0.50993
0.5551 0.535074
2.46 0.547806
e
0.04584 0.0104132
0.383 0.0137034
2.328 0.0259669
e
0.01638 0.0685613
0.06709 0.0346713
0.2323 0.0174672
1.841 0.00877049
e
0.01537 0.075287
0.07541 0.0382263
0.433 0.0192779
4.443 0.00968296
e
0.1039 0.179296
0.4762 0.097721
3.613 0.050799
e
0.01168 0.0605786
0.1381 0.0301953
0.3859 0.0151451
1.572 0.00757736
e
0.02221 0.267956
0.3562 0.258753
2.143 0.259484
6.445 0.243291
e
0.1038 1.55055
0.4252 1.77841
2.553 1.69774
e
set title 'sweep: influence'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.04558 0.0381945
0.2157 0.0220039
1.632 0.0116292
e
0.07162 0.024992
0.2339 0.011381
1.842 0.00549853
e
0.06805 0.0701639
0.3354 0.0352164
1.703 0.0176897
e
0.05737 0.06402
0.3611 0.0321181
1.84 0.016143
e
0.06862 0.0841219
0.3068 0.0426694
1.507 0.0215079
e
0.07382 0.0829429
0.3932 0.0419844
1.867 0.0211519
e
set title 'sweep: influence-rf1.5'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.01168 0.0605786
0.1381 0.0301953
0.3859 0.0151451
1.572 0.00757736
e
0.01988 0.0601528
0.08212 0.0301825
0.4148 0.015124
2.332 0.00757202
e
0.01023 0.0598209
0.03749 0.0300272
e
0.009424 0.060652
0.2733 0.0303153
1.614 0.0151651
2.989 0.00758382
e
0.01793 0.061316
0.04044 0.0305339
0.284 0.0152305
2.126 0.00760227
e
0.008704 0.0606604
0.04886 0.0303182
0.3432 0.015166
1.791 0.00758407
e
set title 'sweep: precision'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 adr double', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 3.015 adr float', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-silling m 1.5 adr double', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-silling m 1.5 float', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-silling m 1.5 adr float'
0.006462 0.0966072
0.03842 0.0531654
0.2431 0.0315884
e
0.02399 0.0248073
0.126 0.00470698
1.564 0.019898
e
0.04558 0.0381945
0.2157 0.0220039
1.632 0.0116292
e
0.01638 0.0685613
0.06709 0.0346713
0.2323 0.0174672
1.841 0.00877049
e
0.006926 0.0966072
0.0479 0.0531653
0.5482 0.0315884
e
0.0358 0.0248073
0.1148 0.00470698
1.268 0.019898
e
0.01031 0.0381894
0.06152 0.0219968
0.4045 0.0116189
e
0.05265 0.0381945
0.2465 0.022004
1.315 0.0116292
e
0.01019 0.0381894
0.06161 0.0219968
0.4427 0.0116189
e
0.01216 0.068566
0.06047 0.0346782
0.387 0.0174772
4.855 0.00878461
e
0.01137 0.0685613
0.05306 0.0346713
0.2805 0.0174672
1.227 0.00877049
e
0.008866 0.068566
0.0506 0.0346781
0.3747 0.0174765
3.982 0.00878087
e
set title 'sweep: connectivity'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.04558 0.0381945
0.2157 0.0220039
1.632 0.0116292
e
0.2616 0.0381945
0.2224 0.0220039
1.642 0.0116292
e
0.09875 0.0381945
0.8346 0.0220039
2.193 0.0116292
e
unset multiplot
set output
$all_4 << EOD
0.001847 0.0224708
0.009618 0.00142435
0.06364 0.00863098
0.4486 0.0135493
0.001826 0.111023
0.01004 0.091093
0.06603 0.0815329
0.4776 0.0768498
0.002872 0.0762345
0.01664 0.0412642
0.1125 0.0236726
0.8328 0.0147539
0.002977 0.0627701
0.01739 0.0312362
0.1201 0.015349
0.8821 0.00730116
0.001948 0.00432525
0.009592 0.00126442
0.06044 0.000343664
0.4519 8.90932e-05
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
0.004546 0.00279669
0.02393 0.00094935
0.1521 0.0002704
1.162 7.21053e-05
0.001897 0.104836
0.01068 0.120046
0.07075 0.127525
0.5518 0.131232
0.001793 0.0605541
0.009204 0.067584
0.06273 0.0709282
0.4708 0.0725632
0.001941 0.0755543
0.01013 0.0458173
0.06435 0.0318658
0.4529 0.0250933
0.002532 0.00817292
0.01457 0.0102474
0.101 0.0195711
0.77 0.024276
0.002536 0.118798
0.01446 0.0889353
0.1022 0.0737445
0.7843 0.0660209
0.003207 0.0913111
0.01792 0.0488791
0.1183 0.0277429
0.8426 0.0170456
0.002345 0.000853876
0.01303 0.000234427
0.09041 6.14019e-05
0.7458 1.57136e-05
0.002014 0.00192317
0.01039 0.000593244
0.06824 0.000162166
0.5179 4.24254e-05
0.002409 0.00389634
0.01259 0.00145315
0.07592 0.000430168
0.6102 0.000117084
0.002229 0.00255619
0.01177 0.00087677
0.07433 0.000248026
0.5797 6.52591e-05
0.002418 0.00244963
0.01327 0.000789558
0.08286 0.000218958
0.6697 5.75447e-05
0.002761 0.00201346
0.01761 0.0006222
0.08661 0.000171478
0.6653 4.50065e-05
0.002803 0.00150371
0.01557 0.000447652
0.1069 0.000120797
0.8454 3.13575e-05
0.002583 0.00203879
0.01385 0.000625753
0.09213 0.000172078
0.7344 4.50038e-05
0.001753 0.0224279
0.009542 0.0013205
0.06188 0.00876489
0.4461 0.0136981
0.002865 0.0762675
0.01645 0.0413589
0.1083 0.0238
0.7966 0.0148982
0.002419 0.00286452
0.01205 0.000956629
0.07479 0.000271154
0.5649 7.16783e-05
0.002342 0.000853876
0.01267 0.000234428
0.08782 6.14019e-05
0.7031 1.57136e-05
0.002228 0.00286452
0.01164 0.000956629
0.07314 0.000271154
0.5252 7.16783e-05
0.005374 0.0028645
0.03009 0.000956626
0.1879 0.000271153
1.356 7.16781e-05
0.004958 0.00446583
0.02943 0.00137769
0.2233 0.000377473
1.989 9.84119e-05
0.003074 0.00412922
0.01758 0.00129305
0.1185 0.000356063
0.9554 9.3103e-05
0.00212 0.00182028
0.01028 0.000704797
0.05935 0.000207752
0.4206 5.56883e-05
0.004721 0.0233922
0.02947 0.00166263
0.2112 0.0085701
1.711 0.0135337
0.002776 0.023204
0.01685 0.0016149
0.1154 0.00858241
0.8806 0.0135368
0.001582 0.0219287
0.00834 0.00128135
0.05236 0.00866764
0.3954 0.0135586
0.002254 0.00286452
0.01144 0.000956629
0.07461 0.000271154
0.6519 7.16783e-05
0.001752 0.0224708
0.009643 0.00142435
0.06367 0.00863098
0.4806 0.0135493
EOD
$front_4 << EOD
0.001948 0.00432525 "corr-none"
0.002014 0.00192317 "corr-silling"
0.00212 0.00182028 "corr-silling"
0.002342 0.000853876 "corr-silling"
0.01028 0.000704797 "corr-silling"
0.01039 0.000593244 "corr-silling"
0.01267 0.000234428 "corr-silling"
0.01303 0.000234427 "corr-silling"
0.05935 0.000207752 "corr-silling"
0.06824 0.000162166 "corr-silling"
0.08782 6.14019e-05 "corr-silling"
0.4206 5.56883e-05 "corr-silling"
0.5179 4.24254e-05 "corr-silling"
0.7031 1.57136e-05 "corr-silling"
EOD
set terminal term size 1560,1260 noenhanced font ',9'
set output 'wave.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 3,3 title 'wave: standing wave in a bar (frequency)'
set title 'sweep: model'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.001847 0.0224708
0.009618 0.00142435
0.06364 0.00863098
0.4486 0.0135493
e
0.001826 0.111023
0.01004 0.091093
0.06603 0.0815329
0.4776 0.0768498
e
0.002872 0.0762345
0.01664 0.0412642
0.1125 0.0236726
0.8328 0.0147539
e
0.002977 0.0627701
0.01739 0.0312362
0.1201 0.015349
0.8821 0.00730116
e
0.001948 0.00432525
0.009592 0.00126442
0.06044 0.000343664
0.4519 8.90932e-05
e
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.004546 0.00279669
0.02393 0.00094935
0.1521 0.0002704
1.162 7.21053e-05
e
set title 'sweep: m'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.001897 0.104836
0.01068 0.120046
0.07075 0.127525
0.5518 0.131232
e
0.001793 0.0605541
0.009204 0.067584
0.06273 0.0709282
0.4708 0.0725632
e
0.001941 0.0755543
0.01013 0.0458173
0.06435 0.0318658
0.4529 0.0250933
e
0.002532 0.00817292
0.01457 0.0102474
0.101 0.0195711
0.77 0.024276
e
0.002536 0.118798
0.01446 0.0889353
0.1022 0.0737445
0.7843 0.0660209
e
0.003207 0.0913111
0.01792 0.0488791
0.1183 0.0277429
0.8426 0.0170456
e
0.002345 0.000853876
0.01303 0.000234427
0.09041 6.14019e-05
0.7458 1.57136e-05
e
0.002014 0.00192317
0.01039 0.000593244
0.06824 0.000162166
0.5179 4.24254e-05
e
0.002409 0.00389634
0.01259 0.00145315
0.07592 0.000430168
0.6102 0.000117084
e
set title 'sweep: influence'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.002229 0.00255619
0.01177 0.00087677
0.07433 0.000248026
0.5797 6.52591e-05
e
0.002418 0.00244963
0.01327 0.000789558
0.08286 0.000218958
0.6697 5.75447e-05
e
0.002761 0.00201346
0.01761 0.0006222
0.08661 0.000171478
0.6653 4.50065e-05
e
0.002803 0.00150371
0.01557 0.000447652
0.1069 0.000120797
0.8454 3.13575e-05
e
0.002583 0.00203879
0.01385 0.000625753
0.09213 0.000172078
0.7344 4.50038e-05
e
set title 'sweep: precision'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 1.5 float'
0.001847 0.0224708
0.009618 0.00142435
0.06364 0.00863098
0.4486 0.0135493
e
0.002872 0.0762345
0.01664 0.0412642
0.1125 0.0236726
0.8328 0.0147539
e
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.002345 0.000853876
0.01303 0.000234427
0.09041 6.14019e-05
0.7458 1.57136e-05
e
0.001753 0.0224279
0.009542 0.0013205
0.06188 0.00876489
0.4461 0.0136981
e
0.002865 0.0762675
0.01645 0.0413589
0.1083 0.0238
0.7966 0.0148982
e
0.002419 0.00286452
0.01205 0.000956629
0.07479 0.000271154
0.5649 7.16783e-05
e
0.002342 0.000853876
0.01267 0.000234428
0.08782 6.14019e-05
0.7031 1.57136e-05
e
set title 'sweep: connectivity'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.002228 0.00286452
0.01164 0.000956629
0.07314 0.000271154
0.5252 7.16783e-05
e
0.005374 0.0028645
0.03009 0.000956626
0.1879 0.000271153
1.356 7.16781e-05
e
set title 'sweep: dt'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb safety 0.8', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling safety 0.8', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling safety 0.2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling safety 0.4', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-silling safety 1', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'pmb safety 0.2', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'pmb safety 0.4', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'pmb safety 1'
0.001847 0.0224708
0.009618 0.00142435
0.06364 0.00863098
0.4486 0.0135493
e
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.004958 0.00446583
0.02943 0.00137769
0.2233 0.000377473
1.989 9.84119e-05
e
0.003074 0.00412922
0.01758 0.00129305
0.1185 0.000356063
0.9554 9.3103e-05
e
0.00212 0.00182028
0.01028 0.000704797
0.05935 0.000207752
0.4206 5.56883e-05
e
0.004721 0.0233922
0.02947 0.00166263
0.2112 0.0085701
1.711 0.0135337
e
0.002776 0.023204
0.01685 0.0016149
0.1154 0.00858241
0.8806 0.0135368
e
0.001582 0.0219287
0.00834 0.00128135
0.05236 0.00866764
0.3954 0.0135586
e
set title 'sweep: order'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb morton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling morton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling lattice', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb lattice'
0.001847 0.0224708
0.009618 0.00142435
0.06364 0.00863098
0.4486 0.0135493
e
0.002262 0.00286452
0.01114 0.000956629
0.06964 0.000271154
0.5907 7.16783e-05
e
0.002254 0.00286452
0.01144 0.000956629
0.07461 0.000271154
0.6519 7.16783e-05
e
0.001752 0.0224708
0.009643 0.00142435
0.06367 0.00863098
0.4806 0.0135493
e
unset multiplot
set output
$all_5 << EOD
0.05708 0.390178
0.4218 0.339095
2.595 0.244481
0.1982 0.308139
0.8361 0.196165
3.671 0.0824364
0.1981 0.533681
0.9838 0.420568
6.906 0.320695
0.2493 0.51248
1.35 0.412628
6.776 0.303488
0.1048 0.0622503
0.7089 0.292488
3.704 0.687491
0.1181 0.415254
1.11 0.279536
5.551 0.21749
0.4106 0.384284
6.578 0.276365
19.21 0.216883
0.02131 0.466931
0.1457 0.406714
0.6751 0.330688
2.436 0.242284
0.01232 0.44057
0.07306 0.342947
0.4204 0.238028
4.22 0.104971
0.03873 0.145724
0.2524 0.146552
0.01976 0.375309
0.1247 0.255415
1.494 0.125387
6.702 0.029021
0.03438 0.506762
0.1999 0.395818
1.644 0.269266
10.83 0.11095
0.3592 0.532192
1.168 0.426641
0.01758 0.350017
0.09097 0.292287
0.5066 0.177294
4.806 0.0517944
0.03957 0.378525
0.2593 0.300901
3.277 0.200412
9.814 0.0563681
0.1536 0.336706
0.9789 0.27608
0.2192 0.392877
0.5541 0.264265
3.477 0.206586
0.08339 0.367349
0.4219 0.254476
3.323 0.190857
0.1381 0.335052
0.4757 0.244522
2.735 0.185088
0.08276 0.32135
0.6365 0.263281
3.59 0.162179
0.09886 0.34011
0.4782 0.248308
4.326 0.173915
0.1215 0.390168
0.392 0.339084
2.029 0.244471
0.1967 0.533671
1.021 0.420558
5.758 0.320684
0.0227 0.415253
0.1138 0.279533
0.6982 0.217483
0.1253 0.415254
0.6225 0.279536
4.162 0.21749
0.02696 0.415256
0.1334 0.279532
0.7656 0.217497
0.01511 0.350015
0.1061 0.292287
0.745 0.177287
10.22 0.0517835
0.03433 0.350017
0.4181 0.292287
1.342 0.177294
12.49 0.0517944
0.01316 0.350015
0.09163 0.292283
0.694 0.177288
9.521 0.0518027
0.116 0.415254
0.612 0.279536
3.784 0.21749
0.4707 0.415654
2.717 0.280186
12.22 0.218248
0.01302 0.390178
0.08596 0.339099
0.6502 0.244488
EOD
$front_5 << EOD
0.01232 0.44057 "pmb"
0.01302 0.390178 "pmb"
0.01316 0.350015 "corr-silling"
0.01511 0.350015 "corr-silling"
0.07306 0.342947 "pmb"
0.08276 0.32135 "corr-silling"
0.09097 0.292287 "corr-silling"
0.09163 0.292283 "corr-silling"
0.1247 0.255415 "lps"
0.4204 0.238028 "pmb"
0.5066 0.177294 "corr-silling"
0.694 0.177288 "corr-silling"
0.745 0.177287 "corr-silling"
1.494 0.125387 "lps"
3.671 0.0824364 "pmb-pv"
4.806 0.0517944 "corr-silling"
6.702 0.029021 "lps"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'hole.png.part'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'hole: plate with a hole, d/W = 0.2 (stress concentration 3.14)'
set title 'sweep: model'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.05708 0.390178
0.4218 0.339095
2.595 0.244481
e
0.1982 0.308139
0.8361 0.196165
3.671 0.0824364
e
0.1981 0.533681
0.9838 0.420568
6.906 0.320695
e
0.2493 0.51248
1.35 0.412628
6.776 0.303488
e
0.1048 0.0622503
0.7089 0.292488
3.704 0.687491
e
0.1181 0.415254
1.11 0.279536
5.551 0.21749
e
0.4106 0.384284
6.578 0.276365
19.21 0.216883
e
set title 'sweep: m'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.02131 0.466931
0.1457 0.406714
0.6751 0.330688
2.436 0.242284
e
0.01232 0.44057
0.07306 0.342947
0.4204 0.238028
4.22 0.104971
e
0.03873 0.145724
0.2524 0.146552
e
0.01976 0.375309
0.1247 0.255415
1.494 0.125387
6.702 0.029021
e
0.03438 0.506762
0.1999 0.395818
1.644 0.269266
10.83 0.11095
e
0.3592 0.532192
1.168 0.426641
e
0.01758 0.350017
0.09097 0.292287
0.5066 0.177294
4.806 0.0517944
e
0.03957 0.378525
0.2593 0.300901
3.277 0.200412
9.814 0.0563681
e
0.1536 0.336706
0.9789 0.27608
e
set title 'sweep: influence'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.1181 0.415254
1.11 0.279536
5.551 0.21749
e
0.2192 0.392877
0.5541 0.264265
3.477 0.206586
e
0.08339 0.367349
0.4219 0.254476
3.323 0.190857
e
0.1381 0.335052
0.4757 0.244522
2.735 0.185088
e
0.08276 0.32135
0.6365 0.263281
3.59 0.162179
e
0.09886 0.34011
0.4782 0.248308
4.326 0.173915
e
set title 'sweep: precision'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 3.015 double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps m 3.015 double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling m 3.015 double', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling m 1.5 double', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'pmb m 3.015 float', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 3.015 float', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 3.015 adr double', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 3.015 float', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 3.015 adr float', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-silling m 1.5 adr double', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-silling m 1.5 float', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-silling m 1.5 adr float'
0.05708 0.390178
0.4218 0.339095
2.595 0.244481
e
0.1981 0.533681
0.9838 0.420568
6.906 0.320695
e
0.1181 0.415254
1.11 0.279536
5.551 0.21749
e
0.01758 0.350017
0.09097 0.292287
0.5066 0.177294
4.806 0.0517944
e
0.1215 0.390168
0.392 0.339084
2.029 0.244471
e
0.1967 0.533671
1.021 0.420558
5.758 0.320684
e
0.0227 0.415253
0.1138 0.279533
0.6982 0.217483
e
0.1253 0.415254
0.6225 0.279536
4.162 0.21749
e
0.02696 0.415256
0.1334 0.279532
0.7656 0.217497
e
0.01511 0.350015
0.1061 0.292287
0.745 0.177287
10.22 0.0517835
e
0.03433 0.350017
0.4181 0.292287
1.342 0.177294
12.49 0.0517944
e
0.01316 0.350015
0.09163 0.292283
0.694 0.177288
9.521 0.0518027
e
set title 'sweep: connectivity'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1181 0.415254
1.11 0.279536
5.551 0.21749
e
0.116 0.415254
0.612 0.279536
3.784 0.21749
e
0.4707 0.415654
2.717 0.280186
12.22 0.218248
e
set title 'sweep: solver'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.05708 0.390178
0.4218 0.339095
2.595 0.244481
e
0.1181 0.415254
1.11 0.279536
5.551 0.21749
e
0.0227 0.415253
0.1138 0.279533
0.6982 0.217483
e
0.01302 0.390178
0.08596 0.339099
0.6502 0.244488
e
unset multiplot
set output
