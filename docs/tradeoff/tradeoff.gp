# Written by bench/tradeoff (tradeoff --plot-only rewrites it from tradeoff.csv).
# Run in this directory: gnuplot tradeoff.gp
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { term = 'pngcairo' } else { term = 'png' }
$all_0 << EOD
0.01235 0.0526401
0.0424 0.0219962
0.3583 0.0244749
0.01732 0.178404
0.05497 0.134232
0.3487 0.123968
0.09823 0.0630069
0.2458 0.0161993
1.72 0.010472
0.09012 0.0571288
0.2526 0.0135638
1.033 0.00389021
0.1257 1.03552
0.8003 0.0979018
0.9718 0.0180732
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
0.1728 0.368073
0.5004 0.0651633
2.942 0.0146724
0.001464 0.177435
0.009065 0.177474
0.05397 0.176023
0.8612 0.174937
0.03418 0.136163
0.1522 0.132972
0.4666 0.131363
0.6294 0.130298
0.03615 0.147234
0.1039 0.0554027
0.008275 0.0596597
0.03734 0.0543234
0.1698 0.0528011
1.378 0.0522031
0.02259 0.13007
0.09238 0.123857
0.421 0.121462
2.166 0.120138
0.1911 0.112953
0.4613 0.0251173
0.01221 0.0460995
0.04841 0.0105921
0.2041 0.00257184
0.9351 0.00063574
0.01565 0.136182
0.05348 0.0295334
0.2299 0.00705136
1.627 0.00173293
0.2203 0.596417
0.4584 0.0989017
0.009915 0.0670127
0.1428 0.0143063
0.9086 0.00340344
1.01 0.000835503
0.02819 0.261251
0.08152 0.042566
0.382 0.00953545
3.992 0.00229907
0.189 5.58737
0.4808 0.24322
0.09434 0.246481
0.2148 0.0490536
1.489 0.0114218
0.1569 0.197164
0.2363 0.0409418
0.9645 0.00963905
0.1 0.154906
0.2449 0.0325253
0.9316 0.00769165
0.08637 0.0932408
0.3619 0.0209143
1.035 0.00503757
0.1567 0.144951
0.5779 0.031174
1.047 0.00741586
0.01708 0.0526401
0.06184 0.0219962
0.2963 0.0244749
0.09475 0.0630069
0.2498 0.0161993
0.9457 0.010472
0.01488 0.290748
0.05074 0.0558507
0.1496 0.0128874
0.07019 0.290749
0.2408 0.0558505
1.275 0.0128881
0.01565 0.290748
0.04882 0.0558499
0.1586 0.0128875
0.004921 0.0460989
0.01907 0.0105915
0.09194 0.00257117
1.15 0.000634844
0.01823 0.0460995
0.1857 0.0105921
0.8889 0.00257184
2.236 0.000635739
0.00849 0.0460989
0.03211 0.0105927
0.1367 0.00257255
0.9323 0.000636578
0.07525 0.290749
0.2515 0.0558505
1.141 0.0128881
0.1975 0.290749
0.5418 0.0558509
3.262 0.0128885
0.005813 0.0526411
0.01936 0.0219926
0.0819 0.0244775
EOD
$front_0 << EOD
0.001464 0.177435 "pmb"
0.004921 0.0460989 "corr-silling"
0.00849 0.0460989 "corr-silling"
0.01907 0.0105915 "corr-silling"
0.09194 0.00257117 "corr-silling"
0.9323 0.000636578 "corr-silling"
0.9351 0.00063574 "corr-silling"
1.15 0.000634844 "corr-silling"
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
0.01235 0.0526401
0.0424 0.0219962
0.3583 0.0244749
e
0.01732 0.178404
0.05497 0.134232
0.3487 0.123968
e
0.09823 0.0630069
0.2458 0.0161993
1.72 0.010472
e
0.09012 0.0571288
0.2526 0.0135638
1.033 0.00389021
e
0.1257 1.03552
0.8003 0.0979018
0.9718 0.0180732
e
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
e
0.1728 0.368073
0.5004 0.0651633
2.942 0.0146724
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
0.001464 0.177435
0.009065 0.177474
0.05397 0.176023
0.8612 0.174937
e
0.03418 0.136163
0.1522 0.132972
0.4666 0.131363
0.6294 0.130298
e
0.03615 0.147234
0.1039 0.0554027
e
0.008275 0.0596597
0.03734 0.0543234
0.1698 0.0528011
1.378 0.0522031
e
0.02259 0.13007
0.09238 0.123857
0.421 0.121462
2.166 0.120138
e
0.1911 0.112953
0.4613 0.0251173
e
0.01221 0.0460995
0.04841 0.0105921
0.2041 0.00257184
0.9351 0.00063574
e
0.01565 0.136182
0.05348 0.0295334
0.2299 0.00705136
1.627 0.00173293
e
0.2203 0.596417
0.4584 0.0989017
e
0.009915 0.0670127
0.1428 0.0143063
0.9086 0.00340344
1.01 0.000835503
e
0.02819 0.261251
0.08152 0.042566
0.382 0.00953545
3.992 0.00229907
e
0.189 5.58737
0.4808 0.24322
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
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
e
0.09434 0.246481
0.2148 0.0490536
1.489 0.0114218
e
0.1569 0.197164
0.2363 0.0409418
0.9645 0.00963905
e
0.1 0.154906
0.2449 0.0325253
0.9316 0.00769165
e
0.08637 0.0932408
0.3619 0.0209143
1.035 0.00503757
e
0.1567 0.144951
0.5779 0.031174
1.047 0.00741586
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
0.01235 0.0526401
0.0424 0.0219962
0.3583 0.0244749
e
0.09823 0.0630069
0.2458 0.0161993
1.72 0.010472
e
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
e
0.01221 0.0460995
0.04841 0.0105921
0.2041 0.00257184
0.9351 0.00063574
e
0.01708 0.0526401
0.06184 0.0219962
0.2963 0.0244749
e
0.09475 0.0630069
0.2498 0.0161993
0.9457 0.010472
e
0.01488 0.290748
0.05074 0.0558507
0.1496 0.0128874
e
0.07019 0.290749
0.2408 0.0558505
1.275 0.0128881
e
0.01565 0.290748
0.04882 0.0558499
0.1586 0.0128875
e
0.004921 0.0460989
0.01907 0.0105915
0.09194 0.00257117
1.15 0.000634844
e
0.01823 0.0460995
0.1857 0.0105921
0.8889 0.00257184
2.236 0.000635739
e
0.00849 0.0460989
0.03211 0.0105927
0.1367 0.00257255
0.9323 0.000636578
e
set title 'sweep: connectivity'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
e
0.07525 0.290749
0.2515 0.0558505
1.141 0.0128881
e
0.1975 0.290749
0.5418 0.0558509
3.262 0.0128885
e
set title 'sweep: solver'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.01235 0.0526401
0.0424 0.0219962
0.3583 0.0244749
e
0.1014 0.290749
0.2674 0.0558505
1.952 0.0128881
e
0.01488 0.290748
0.05074 0.0558507
0.1496 0.0128874
e
0.005813 0.0526411
0.01936 0.0219926
0.0819 0.0244775
e
unset multiplot
set output
$all_1 << EOD
0.04432 0.0507224
0.1832 0.00819064
0.5009 0.0136069
0.01497 0.241824
0.08863 0.202483
0.9636 0.18231
0.1063 0.0832629
0.2676 0.050905
2 0.0341128
0.0566 0.0721965
0.2814 0.0357857
2.032 0.0168654
0.2447 0.525384
0.7646 0.534887
2.479 0.566492
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
0.1057 0.00132589
0.8356 0.00168468
2.994 0.00101277
0.002745 0.252515
0.0167 0.238393
0.08177 0.23109
0.5488 0.227377
0.007047 0.138175
0.03752 0.135877
0.3189 0.134639
1.398 0.133997
0.02089 0.2734
0.1028 0.157715
0.6261 0.0984242
0.04427 0.00568258
0.401 0.0426014
0.3791 0.0678351
2.174 0.0807372
0.02002 0.217227
0.08727 0.185566
0.8484 0.169125
3.736 0.160748
0.09357 0.0471587
0.4076 0.0325057
3.17 0.0253418
0.03552 0.0751876
0.199 0.038408
0.3111 0.0194306
2.625 0.00977488
0.02335 0.0742747
0.2266 0.0381068
1.027 0.0193113
4.757 0.00972214
0.08236 0.0977401
0.9914 0.0515511
2.903 0.026214
0.01249 0.071177
0.06237 0.0364808
0.2849 0.0185076
3.269 0.00931563
0.02286 0.32161
0.1059 0.28303
1.415 0.266232
4.074 0.258404
0.07174 1.13546
0.4835 1.69532
2.675 1.95389
0.07668 0.0378733
0.3338 0.0185499
1.747 0.00926294
0.01278 0.0715705
0.06285 0.0366709
0.3179 0.0185467
3.695 0.00932489
0.07547 0.0715467
0.2864 0.0361211
1.886 0.0182102
0.03012 0.0722435
0.3027 0.0367681
0.05547 0.0652823
0.4986 0.0330262
1.804 0.0166723
0.01246 0.0721246
0.06883 0.0367579
0.3437 0.0185616
2.19 0.00932757
0.04548 0.0837893
0.5378 0.0428115
2.542 0.0216584
0.01133 0.0720388
0.06634 0.0367397
0.3296 0.0185574
2.459 0.00932651
0.141 0.0812775
0.604 0.0413515
1.389 0.0208994
0.01116 0.0721226
0.08335 0.0367575
0.2692 0.0185615
2.46 0.00932755
0.01456 0.0511258
0.0684 0.00857885
1.4 0.0132261
0.1939 0.0827449
0.8414 0.0504176
1.32 0.0336376
0.01366 0.00644759
0.07649 0.00433091
0.4081 0.00233902
0.05266 0.00644517
0.2579 0.00432651
1.371 0.0023388
0.01407 0.00644185
0.07854 0.00432202
0.3039 0.00234598
0.006782 0.0751849
0.03976 0.0384033
0.2977 0.0194375
4.592 0.00978471
0.009642 0.0751876
0.05357 0.038408
0.3437 0.0194306
4.571 0.00977488
0.01176 0.0751907
0.0523 0.0384034
0.2799 0.0194369
4.453 0.00976612
0.05266 0.00644496
0.2326 0.0043265
1.335 0.00233881
0.1081 0.00644549
0.4019 0.00432679
2.27 0.00233895
0.006199 0.0507186
0.03386 0.00818543
0.2079 0.0136144
EOD
$front_1 << EOD
0.002745 0.252515 "pmb"
0.006199 0.0507186 "pmb"
0.01366 0.00644759 "corr-silling"
0.01407 0.00644185 "corr-silling"
0.04427 0.00568258 "lps"
0.07649 0.00433091 "corr-silling"
0.07854 0.00432202 "corr-silling"
0.1057 0.00132589 "corr-hourglass"
2.994 0.00101277 "corr-hourglass"
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
0.04432 0.0507224
0.1832 0.00819064
0.5009 0.0136069
e
0.01497 0.241824
0.08863 0.202483
0.9636 0.18231
e
0.1063 0.0832629
0.2676 0.050905
2 0.0341128
e
0.0566 0.0721965
0.2814 0.0357857
2.032 0.0168654
e
0.2447 0.525384
0.7646 0.534887
2.479 0.566492
e
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
e
0.1057 0.00132589
0.8356 0.00168468
2.994 0.00101277
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
0.002745 0.252515
0.0167 0.238393
0.08177 0.23109
0.5488 0.227377
e
0.007047 0.138175
0.03752 0.135877
0.3189 0.134639
1.398 0.133997
e
0.02089 0.2734
0.1028 0.157715
0.6261 0.0984242
e
0.04427 0.00568258
0.401 0.0426014
0.3791 0.0678351
2.174 0.0807372
e
0.02002 0.217227
0.08727 0.185566
0.8484 0.169125
3.736 0.160748
e
0.09357 0.0471587
0.4076 0.0325057
3.17 0.0253418
e
0.03552 0.0751876
0.199 0.038408
0.3111 0.0194306
2.625 0.00977488
e
0.02335 0.0742747
0.2266 0.0381068
1.027 0.0193113
4.757 0.00972214
e
0.08236 0.0977401
0.9914 0.0515511
2.903 0.026214
e
0.01249 0.071177
0.06237 0.0364808
0.2849 0.0185076
3.269 0.00931563
e
0.02286 0.32161
0.1059 0.28303
1.415 0.266232
4.074 0.258404
e
0.07174 1.13546
0.4835 1.69532
2.675 1.95389
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
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
e
0.07668 0.0378733
0.3338 0.0185499
1.747 0.00926294
e
0.07547 0.0715467
0.2864 0.0361211
1.886 0.0182102
e
0.05547 0.0652823
0.4986 0.0330262
1.804 0.0166723
e
0.04548 0.0837893
0.5378 0.0428115
2.542 0.0216584
e
0.141 0.0812775
0.604 0.0413515
1.389 0.0208994
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
0.01249 0.071177
0.06237 0.0364808
0.2849 0.0185076
3.269 0.00931563
e
0.01278 0.0715705
0.06285 0.0366709
0.3179 0.0185467
3.695 0.00932489
e
0.03012 0.0722435
0.3027 0.0367681
e
0.01246 0.0721246
0.06883 0.0367579
0.3437 0.0185616
2.19 0.00932757
e
0.01133 0.0720388
0.06634 0.0367397
0.3296 0.0185574
2.459 0.00932651
e
0.01116 0.0721226
0.08335 0.0367575
0.2692 0.0185615
2.46 0.00932755
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
0.04432 0.0507224
0.1832 0.00819064
0.5009 0.0136069
e
0.1063 0.0832629
0.2676 0.050905
2 0.0341128
e
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
e
0.03552 0.0751876
0.199 0.038408
0.3111 0.0194306
2.625 0.00977488
e
0.01456 0.0511258
0.0684 0.00857885
1.4 0.0132261
e
0.1939 0.0827449
0.8414 0.0504176
1.32 0.0336376
e
0.01366 0.00644759
0.07649 0.00433091
0.4081 0.00233902
e
0.05266 0.00644517
0.2579 0.00432651
1.371 0.0023388
e
0.01407 0.00644185
0.07854 0.00432202
0.3039 0.00234598
e
0.006782 0.0751849
0.03976 0.0384033
0.2977 0.0194375
4.592 0.00978471
e
0.009642 0.0751876
0.05357 0.038408
0.3437 0.0194306
4.571 0.00977488
e
0.01176 0.0751907
0.0523 0.0384034
0.2799 0.0194369
4.453 0.00976612
e
set title 'sweep: connectivity'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
e
0.05266 0.00644496
0.2326 0.0043265
1.335 0.00233881
e
0.1081 0.00644549
0.4019 0.00432679
2.27 0.00233895
e
set title 'sweep: solver'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.04432 0.0507224
0.1832 0.00819064
0.5009 0.0136069
e
0.06569 0.00644496
0.2784 0.0043265
1.403 0.00233881
e
0.01366 0.00644759
0.07649 0.00433091
0.4081 0.00233902
e
0.006199 0.0507186
0.03386 0.00818543
0.2079 0.0136144
e
unset multiplot
set output
$all_2 << EOD
0.01679 0.0745181
0.08088 0.025769
0.5154 0.000734461
0.01648 0.251204
0.08772 0.206294
0.5085 0.183248
0.07137 0.0672679
0.3186 0.0344628
1.371 0.0174871
0.06466 0.072804
0.2612 0.0373563
1.677 0.0189543
0.06767 0.541587
0.349 0.55146
1.346 0.584148
0.06774 0.00808447
0.2728 0.00456743
1.55 0.00237018
0.1264 0.00185344
0.9199 0.00137971
3.501 0.000765259
0.003689 0.29338
0.01773 0.281062
0.1263 0.274639
0.6037 0.271356
0.00729 0.0352363
0.03575 0.0325047
0.193 0.0310583
2.339 0.0303141
0.02526 0.319099
0.1341 0.18725
0.7278 0.119641
0.01171 0.0820064
0.06982 0.0420977
0.3257 0.0213322
1.781 0.0107378
0.02286 0.0781639
0.1147 0.0402866
0.563 0.0204733
3.532 0.0103208
0.09983 0.0384446
0.4561 0.0191922
2.414 0.00970004
0.01297 0.0750447
0.06391 0.0384022
1.917 0.019433
2.242 0.00977594
0.02482 0.0744236
0.124 0.0381628
0.648 0.0193272
3.356 0.00972627
0.1101 0.101232
1.475 0.0518795
2.582 0.0261933
0.06891 0.0363258
0.2846 0.0183265
1.439 0.0092307
0.07425 0.070515
0.2816 0.0359856
1.493 0.0181922
0.06857 0.06458
0.2854 0.0329743
2.088 0.0166761
0.0656 0.0835806
0.6032 0.042791
1.564 0.021657
0.07008 0.0807289
0.2737 0.0412969
3.27 0.0208961
0.01562 0.0749388
0.08307 0.0261678
0.4366 0.00112275
0.06483 0.0667582
0.2764 0.0339756
1.407 0.0170081
0.01341 0.0080828
0.08232 0.00456249
0.321 0.00236439
0.05052 0.00808467
0.2985 0.00456743
1.905 0.00237018
0.02777 0.00808103
0.1107 0.00457257
0.349 0.00237711
0.009882 0.075043
0.03766 0.0383996
0.2619 0.01944
4.191 0.00978582
0.01029 0.0750447
0.1502 0.0384022
1.684 0.019433
3.368 0.00977594
0.02224 0.0750417
0.06259 0.0383978
0.2956 0.0194393
4.694 0.00976626
EOD
$front_2 << EOD
0.003689 0.29338 "pmb"
0.00729 0.0352363 "pmb"
0.01341 0.0080828 "corr-silling"
0.02777 0.00808103 "corr-silling"
0.08232 0.00456249 "corr-silling"
0.1264 0.00185344 "corr-hourglass"
0.4366 0.00112275 "pmb"
0.5154 0.000734461 "pmb"
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
0.01679 0.0745181
0.08088 0.025769
0.5154 0.000734461
e
0.01648 0.251204
0.08772 0.206294
0.5085 0.183248
e
0.07137 0.0672679
0.3186 0.0344628
1.371 0.0174871
e
0.06466 0.072804
0.2612 0.0373563
1.677 0.0189543
e
0.06767 0.541587
0.349 0.55146
1.346 0.584148
e
0.06774 0.00808447
0.2728 0.00456743
1.55 0.00237018
e
0.1264 0.00185344
0.9199 0.00137971
3.501 0.000765259
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
0.003689 0.29338
0.01773 0.281062
0.1263 0.274639
0.6037 0.271356
e
0.00729 0.0352363
0.03575 0.0325047
0.193 0.0310583
2.339 0.0303141
e
0.02526 0.319099
0.1341 0.18725
0.7278 0.119641
e
0.01171 0.0820064
0.06982 0.0420977
0.3257 0.0213322
1.781 0.0107378
e
0.02286 0.0781639
0.1147 0.0402866
0.563 0.0204733
3.532 0.0103208
e
0.09983 0.0384446
0.4561 0.0191922
2.414 0.00970004
e
0.01297 0.0750447
0.06391 0.0384022
1.917 0.019433
2.242 0.00977594
e
0.02482 0.0744236
0.124 0.0381628
0.648 0.0193272
3.356 0.00972627
e
0.1101 0.101232
1.475 0.0518795
2.582 0.0261933
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
0.06774 0.00808447
0.2728 0.00456743
1.55 0.00237018
e
0.06891 0.0363258
0.2846 0.0183265
1.439 0.0092307
e
0.07425 0.070515
0.2816 0.0359856
1.493 0.0181922
e
0.06857 0.06458
0.2854 0.0329743
2.088 0.0166761
e
0.0656 0.0835806
0.6032 0.042791
1.564 0.021657
e
0.07008 0.0807289
0.2737 0.0412969
3.27 0.0208961
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
0.01679 0.0745181
0.08088 0.025769
0.5154 0.000734461
e
0.07137 0.0672679
0.3186 0.0344628
1.371 0.0174871
e
0.06774 0.00808447
0.2728 0.00456743
1.55 0.00237018
e
0.01297 0.0750447
0.06391 0.0384022
1.917 0.019433
2.242 0.00977594
e
0.01562 0.0749388
0.08307 0.0261678
0.4366 0.00112275
e
0.06483 0.0667582
0.2764 0.0339756
1.407 0.0170081
e
0.01341 0.0080828
0.08232 0.00456249
0.321 0.00236439
e
0.05052 0.00808467
0.2985 0.00456743
1.905 0.00237018
e
0.02777 0.00808103
0.1107 0.00457257
0.349 0.00237711
e
0.009882 0.075043
0.03766 0.0383996
0.2619 0.01944
4.191 0.00978582
e
0.01029 0.0750447
0.1502 0.0384022
1.684 0.019433
3.368 0.00977594
e
0.02224 0.0750417
0.06259 0.0383978
0.2956 0.0194393
4.694 0.00976626
e
unset multiplot
set output
$all_3 << EOD
0.01277 0.0966072
0.08515 0.0531654
0.4581 0.0315884
0.01348 0.236483
0.06543 0.195019
0.347 0.174474
0.05619 0.0248073
0.2345 0.00470698
1.195 0.019898
0.0578 0.0675591
0.2409 0.0371671
2.141 0.0213948
0.05722 0.750117
0.386 0.704929
2.452 0.697433
0.06722 0.0381945
0.2887 0.0220039
1.381 0.0116292
0.1079 0.0535838
0.5929 0.0302717
4.16 0.0158957
0.002647 0.380077
0.01614 0.377917
0.363 0.376641
1.866 0.375949
0.007777 0.50843
0.03257 0.510967
0.1896 0.512607
1.006 0.513532
0.02032 0.285843
0.369 0.188191
2.166 0.13995
0.04949 0.19554
0.1262 0.171888
0.2912 0.159429
1.533 0.153008
0.01844 0.460649
0.1897 0.50993
2.1 0.535074
3.235 0.547806
0.1094 0.0104132
0.4503 0.0137034
2.502 0.0259669
0.01243 0.0685613
0.06333 0.0346713
1.063 0.0174672
1.775 0.00877049
0.08205 0.075287
0.6106 0.0382263
0.6758 0.0192779
6.122 0.00968296
0.1107 0.179296
0.457 0.097721
6.896 0.050799
0.06666 0.0605786
0.4802 0.0301953
2.214 0.0151451
5.943 0.00757736
0.02225 0.267956
0.1237 0.258753
0.6311 0.259484
4.662 0.243291
0.09906 1.55055
0.5157 1.77841
2.495 1.69774
0.06763 0.024992
0.271 0.011381
1.391 0.00549853
0.01379 0.0601528
0.06447 0.0301825
0.5381 0.015124
2.043 0.00757202
0.06761 0.0701639
0.2857 0.0352164
3.317 0.0176897
0.07424 0.0598209
0.3495 0.0300272
0.2477 0.06402
1.111 0.0321181
3.219 0.016143
0.01191 0.060652
0.06453 0.0303153
0.3228 0.0151651
2.205 0.00758382
0.06402 0.0841219
0.6196 0.0426694
1.966 0.0215079
0.06301 0.061316
0.3533 0.0305339
1.747 0.0152305
1.851 0.00760227
0.2487 0.0829429
1.098 0.0419844
1.868 0.0211519
0.01295 0.0606604
0.06038 0.0303182
0.2717 0.015166
1.328 0.00758407
0.01343 0.0966072
0.07017 0.0531653
0.3657 0.0315884
0.06041 0.0248073
0.2568 0.00470698
1.214 0.019898
0.01368 0.0381894
0.08197 0.0219968
0.3969 0.0116189
0.1771 0.0381945
0.8421 0.022004
1.358 0.0116292
0.01757 0.0381894
0.1048 0.0219968
0.3868 0.0116189
0.008935 0.068566
0.05264 0.0346782
0.3755 0.0174772
5.234 0.00878458
0.01002 0.0685613
0.07508 0.0346713
0.3429 0.0174672
1.569 0.00877049
0.01822 0.068566
0.1061 0.0346779
0.4348 0.0174765
4.097 0.00878076
0.04593 0.0381945
0.3092 0.0220039
1.456 0.0116292
0.1536 0.0381945
0.4647 0.0220039
2.058 0.0116292
EOD
$front_3 << EOD
0.002647 0.380077 "pmb"
0.008935 0.068566 "corr-silling"
0.01002 0.0685613 "corr-silling"
0.01191 0.060652 "corr-none"
0.01368 0.0381894 "corr-silling"
0.05264 0.0346782 "corr-silling"
0.05619 0.0248073 "lps"
0.08197 0.0219968 "corr-silling"
0.1048 0.0219968 "corr-silling"
0.1094 0.0104132 "lps"
0.2345 0.00470698 "lps"
0.2568 0.00470698 "lps"
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
0.01277 0.0966072
0.08515 0.0531654
0.4581 0.0315884
e
0.01348 0.236483
0.06543 0.195019
0.347 0.174474
e
0.05619 0.0248073
0.2345 0.00470698
1.195 0.019898
e
0.0578 0.0675591
0.2409 0.0371671
2.141 0.0213948
e
0.05722 0.750117
0.386 0.704929
2.452 0.697433
e
0.06722 0.0381945
0.2887 0.0220039
1.381 0.0116292
e
0.1079 0.0535838
0.5929 0.0302717
4.16 0.0158957
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
0.002647 0.380077
0.01614 0.377917
0.363 0.376641
1.866 0.375949
e
0.007777 0.50843
0.03257 0.510967
0.1896 0.512607
1.006 0.513532
e
0.02032 0.285843
0.369 0.188191
2.166 0.13995
e
0.04949 0.19554
0.1262 0.171888
0.2912 0.159429
1.533 0.153008
e
0.01844 0.460649
0.1897 0.50993
2.1 0.535074
3.235 0.547806
e
0.1094 0.0104132
0.4503 0.0137034
2.502 0.0259669
e
0.01243 0.0685613
0.06333 0.0346713
1.063 0.0174672
1.775 0.00877049
e
0.08205 0.075287
0.6106 0.0382263
0.6758 0.0192779
6.122 0.00968296
e
0.1107 0.179296
0.457 0.097721
6.896 0.050799
e
0.06666 0.0605786
0.4802 0.0301953
2.214 0.0151451
5.943 0.00757736
e
0.02225 0.267956
0.1237 0.258753
0.6311 0.259484
4.662 0.243291
e
0.09906 1.55055
0.5157 1.77841
2.495 1.69774
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
0.06722 0.0381945
0.2887 0.0220039
1.381 0.0116292
e
0.06763 0.024992
0.271 0.011381
1.391 0.00549853
e
0.06761 0.0701639
0.2857 0.0352164
3.317 0.0176897
e
0.2477 0.06402
1.111 0.0321181
3.219 0.016143
e
0.06402 0.0841219
0.6196 0.0426694
1.966 0.0215079
e
0.2487 0.0829429
1.098 0.0419844
1.868 0.0211519
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
0.06666 0.0605786
0.4802 0.0301953
2.214 0.0151451
5.943 0.00757736
e
0.01379 0.0601528
0.06447 0.0301825
0.5381 0.015124
2.043 0.00757202
e
0.07424 0.0598209
0.3495 0.0300272
e
0.01191 0.060652
0.06453 0.0303153
0.3228 0.0151651
2.205 0.00758382
e
0.06301 0.061316
0.3533 0.0305339
1.747 0.0152305
1.851 0.00760227
e
0.01295 0.0606604
0.06038 0.0303182
0.2717 0.015166
1.328 0.00758407
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
0.01277 0.0966072
0.08515 0.0531654
0.4581 0.0315884
e
0.05619 0.0248073
0.2345 0.00470698
1.195 0.019898
e
0.06722 0.0381945
0.2887 0.0220039
1.381 0.0116292
e
0.01243 0.0685613
0.06333 0.0346713
1.063 0.0174672
1.775 0.00877049
e
0.01343 0.0966072
0.07017 0.0531653
0.3657 0.0315884
e
0.06041 0.0248073
0.2568 0.00470698
1.214 0.019898
e
0.01368 0.0381894
0.08197 0.0219968
0.3969 0.0116189
e
0.1771 0.0381945
0.8421 0.022004
1.358 0.0116292
e
0.01757 0.0381894
0.1048 0.0219968
0.3868 0.0116189
e
0.008935 0.068566
0.05264 0.0346782
0.3755 0.0174772
5.234 0.00878458
e
0.01002 0.0685613
0.07508 0.0346713
0.3429 0.0174672
1.569 0.00877049
e
0.01822 0.068566
0.1061 0.0346779
0.4348 0.0174765
4.097 0.00878076
e
set title 'sweep: connectivity'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.06722 0.0381945
0.2887 0.0220039
1.381 0.0116292
e
0.04593 0.0381945
0.3092 0.0220039
1.456 0.0116292
e
0.1536 0.0381945
0.4647 0.0220039
2.058 0.0116292
e
unset multiplot
set output
$all_4 << EOD
0.003355 0.0224708
0.01305 0.00142435
0.08206 0.00863098
0.3513 0.0135493
0.001285 0.111023
0.006826 0.091093
0.0442 0.0815329
0.3281 0.0768498
0.002041 0.0762345
0.01119 0.0412642
0.07523 0.0236726
0.5655 0.0147539
0.002114 0.0627701
0.0115 0.0312362
0.07908 0.015349
0.6158 0.00730116
0.001898 0.00432525
0.008851 0.00126442
0.0593 0.000343664
0.5215 8.90932e-05
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
0.003006 0.00279669
0.01616 0.00094935
0.1019 0.0002704
0.8679 7.21053e-05
0.001505 0.104836
0.00715 0.120046
0.04755 0.127525
0.3665 0.131232
0.001318 0.0605541
0.006328 0.067584
0.04286 0.0709282
0.3337 0.0725632
0.001535 0.0755543
0.006566 0.0458173
0.04028 0.0318658
0.2936 0.0250933
0.002261 0.00817292
0.01052 0.0102474
0.07232 0.0195711
0.5516 0.024276
0.001895 0.118798
0.01026 0.0889353
0.07088 0.0737445
0.5455 0.0660209
0.002165 0.0913111
0.01147 0.0488791
0.07373 0.0277429
0.5753 0.0170456
0.002452 0.000853876
0.01325 0.000234427
0.0878 6.14019e-05
0.9001 1.57136e-05
0.001932 0.00192317
0.00973 0.000593244
0.06698 0.000162166
0.6354 4.24254e-05
0.00232 0.00389634
0.01236 0.00145315
0.07597 0.000430168
0.7308 0.000117084
0.002105 0.00255619
0.01179 0.00087677
0.06865 0.000248026
0.6019 6.52591e-05
0.002152 0.00244963
0.01157 0.000789558
0.0781 0.000218958
0.6864 5.75447e-05
0.002486 0.00201346
0.01172 0.0006222
0.08124 0.000171478
0.7414 4.50065e-05
0.002617 0.00150371
0.01425 0.000447652
0.09777 0.000120797
1.023 3.13575e-05
0.002441 0.00203879
0.01265 0.000625753
0.08856 0.000172078
0.8658 4.50038e-05
0.00134 0.0224279
0.007184 0.0013205
0.04421 0.00876489
0.3226 0.0136981
0.00248 0.0762675
0.01196 0.0413589
0.08027 0.0238
0.6183 0.0148982
0.002112 0.00286452
0.01029 0.000956629
0.06578 0.000271154
0.5613 7.16783e-05
0.002302 0.000853875
0.01224 0.000234428
0.08877 6.14019e-05
0.7599 1.57136e-05
0.001988 0.00286452
0.01034 0.000956629
0.06721 0.000271154
0.5493 7.16783e-05
0.003921 0.0028645
0.02207 0.000956626
0.1362 0.000271153
1.035 7.16781e-05
0.00437 0.00446583
0.02685 0.00137769
0.1999 0.000377473
2.172 9.84119e-05
0.003514 0.00412922
0.01678 0.00129305
0.1116 0.000356063
1.021 9.3103e-05
0.001789 0.00182028
0.009166 0.000704797
0.0557 0.000207752
0.4103 5.56883e-05
0.003201 0.0233922
0.01913 0.00166263
0.1399 0.0085701
1.145 0.0135337
0.001993 0.023204
0.01187 0.0016149
0.08369 0.00858241
0.5574 0.0135368
0.001084 0.0219287
0.005695 0.00128135
0.03434 0.00866764
0.2444 0.0135586
0.001994 0.00286452
0.01008 0.000956629
0.06347 0.000271154
0.4777 7.16783e-05
0.001217 0.0224708
0.006331 0.00142435
0.04187 0.00863098
0.3 0.0135493
EOD
$front_4 << EOD
0.001084 0.0219287 "pmb"
0.001789 0.00182028 "corr-silling"
0.002302 0.000853875 "corr-silling"
0.009166 0.000704797 "corr-silling"
0.00973 0.000593244 "corr-silling"
0.01224 0.000234428 "corr-silling"
0.01325 0.000234427 "corr-silling"
0.0557 0.000207752 "corr-silling"
0.06698 0.000162166 "corr-silling"
0.0878 6.14019e-05 "corr-silling"
0.4103 5.56883e-05 "corr-silling"
0.6354 4.24254e-05 "corr-silling"
0.7599 1.57136e-05 "corr-silling"
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
0.003355 0.0224708
0.01305 0.00142435
0.08206 0.00863098
0.3513 0.0135493
e
0.001285 0.111023
0.006826 0.091093
0.0442 0.0815329
0.3281 0.0768498
e
0.002041 0.0762345
0.01119 0.0412642
0.07523 0.0236726
0.5655 0.0147539
e
0.002114 0.0627701
0.0115 0.0312362
0.07908 0.015349
0.6158 0.00730116
e
0.001898 0.00432525
0.008851 0.00126442
0.0593 0.000343664
0.5215 8.90932e-05
e
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.003006 0.00279669
0.01616 0.00094935
0.1019 0.0002704
0.8679 7.21053e-05
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
0.001505 0.104836
0.00715 0.120046
0.04755 0.127525
0.3665 0.131232
e
0.001318 0.0605541
0.006328 0.067584
0.04286 0.0709282
0.3337 0.0725632
e
0.001535 0.0755543
0.006566 0.0458173
0.04028 0.0318658
0.2936 0.0250933
e
0.002261 0.00817292
0.01052 0.0102474
0.07232 0.0195711
0.5516 0.024276
e
0.001895 0.118798
0.01026 0.0889353
0.07088 0.0737445
0.5455 0.0660209
e
0.002165 0.0913111
0.01147 0.0488791
0.07373 0.0277429
0.5753 0.0170456
e
0.002452 0.000853876
0.01325 0.000234427
0.0878 6.14019e-05
0.9001 1.57136e-05
e
0.001932 0.00192317
0.00973 0.000593244
0.06698 0.000162166
0.6354 4.24254e-05
e
0.00232 0.00389634
0.01236 0.00145315
0.07597 0.000430168
0.7308 0.000117084
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
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.002105 0.00255619
0.01179 0.00087677
0.06865 0.000248026
0.6019 6.52591e-05
e
0.002152 0.00244963
0.01157 0.000789558
0.0781 0.000218958
0.6864 5.75447e-05
e
0.002486 0.00201346
0.01172 0.0006222
0.08124 0.000171478
0.7414 4.50065e-05
e
0.002617 0.00150371
0.01425 0.000447652
0.09777 0.000120797
1.023 3.13575e-05
e
0.002441 0.00203879
0.01265 0.000625753
0.08856 0.000172078
0.8658 4.50038e-05
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
0.003355 0.0224708
0.01305 0.00142435
0.08206 0.00863098
0.3513 0.0135493
e
0.002041 0.0762345
0.01119 0.0412642
0.07523 0.0236726
0.5655 0.0147539
e
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.002452 0.000853876
0.01325 0.000234427
0.0878 6.14019e-05
0.9001 1.57136e-05
e
0.00134 0.0224279
0.007184 0.0013205
0.04421 0.00876489
0.3226 0.0136981
e
0.00248 0.0762675
0.01196 0.0413589
0.08027 0.0238
0.6183 0.0148982
e
0.002112 0.00286452
0.01029 0.000956629
0.06578 0.000271154
0.5613 7.16783e-05
e
0.002302 0.000853875
0.01224 0.000234428
0.08877 6.14019e-05
0.7599 1.57136e-05
e
set title 'sweep: connectivity'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.001988 0.00286452
0.01034 0.000956629
0.06721 0.000271154
0.5493 7.16783e-05
e
0.003921 0.0028645
0.02207 0.000956626
0.1362 0.000271153
1.035 7.16781e-05
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
0.003355 0.0224708
0.01305 0.00142435
0.08206 0.00863098
0.3513 0.0135493
e
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.00437 0.00446583
0.02685 0.00137769
0.1999 0.000377473
2.172 9.84119e-05
e
0.003514 0.00412922
0.01678 0.00129305
0.1116 0.000356063
1.021 9.3103e-05
e
0.001789 0.00182028
0.009166 0.000704797
0.0557 0.000207752
0.4103 5.56883e-05
e
0.003201 0.0233922
0.01913 0.00166263
0.1399 0.0085701
1.145 0.0135337
e
0.001993 0.023204
0.01187 0.0016149
0.08369 0.00858241
0.5574 0.0135368
e
0.001084 0.0219287
0.005695 0.00128135
0.03434 0.00866764
0.2444 0.0135586
e
set title 'sweep: order'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb morton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling morton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling lattice', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb lattice'
0.003355 0.0224708
0.01305 0.00142435
0.08206 0.00863098
0.3513 0.0135493
e
0.002038 0.00286452
0.01062 0.000956629
0.06549 0.000271154
0.5886 7.16783e-05
e
0.001994 0.00286452
0.01008 0.000956629
0.06347 0.000271154
0.4777 7.16783e-05
e
0.001217 0.0224708
0.006331 0.00142435
0.04187 0.00863098
0.3 0.0135493
e
unset multiplot
set output
$all_5 << EOD
0.04983 0.390178
0.3233 0.339095
3.453 0.244481
0.05802 0.308139
0.3007 0.196165
3.61 0.0824364
0.186 0.533681
0.8852 0.420568
6.256 0.320695
0.2067 0.51248
0.965 0.412628
5.592 0.303488
0.104 0.0622503
0.9821 0.292488
3.366 0.687491
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
0.3515 0.384284
1.986 0.276365
24.39 0.216883
0.01374 0.466931
0.05029 0.406714
0.5279 0.330688
2.592 0.242284
0.02352 0.44057
0.1148 0.342947
1.464 0.238028
6.43 0.104971
0.07482 0.145724
1.152 0.146552
0.03809 0.375309
0.2734 0.255415
1.287 0.125387
7.627 0.029021
0.07793 0.506762
0.4384 0.395818
3.782 0.269266
17.63 0.11095
0.3061 0.532192
2.247 0.426641
0.02622 0.350017
0.1534 0.292287
1.255 0.177294
6.242 0.0517944
0.05166 0.378525
0.2555 0.300901
6.268 0.200412
13.7 0.0563681
0.4406 0.336706
0.9813 0.27608
0.1228 0.392877
0.5881 0.264265
4.157 0.206586
0.1721 0.367349
0.6894 0.254476
3.259 0.190857
0.1198 0.335052
0.9247 0.244522
3.137 0.185088
0.1401 0.32135
0.7084 0.263281
3.314 0.162179
0.1202 0.34011
0.5423 0.248308
4.249 0.173915
0.05358 0.390168
0.3141 0.339084
3.08 0.244471
0.2158 0.533671
0.9167 0.420558
6.202 0.320684
0.02456 0.415256
0.1194 0.279532
0.8271 0.217496
0.09628 0.415254
0.5427 0.279536
3.124 0.21749
0.03186 0.415252
0.1154 0.279541
0.8413 0.217496
0.01377 0.350019
0.1032 0.292283
0.7689 0.177295
10.87 0.0517827
0.02195 0.350017
0.1528 0.292287
2.126 0.177294
12.15 0.0517944
0.02075 0.350019
0.09158 0.292291
0.7228 0.177288
10.93 0.0517919
0.2751 0.415254
0.5547 0.279536
3.543 0.21749
0.3974 0.415654
2.606 0.280186
11.3 0.218248
0.008818 0.390178
0.05607 0.339099
0.4002 0.244488
EOD
$front_5 << EOD
0.008818 0.390178 "pmb"
0.01377 0.350019 "corr-silling"
0.02195 0.350017 "corr-silling"
0.05607 0.339099 "pmb"
0.05802 0.308139 "pmb-pv"
0.07482 0.145724 "pmb"
0.104 0.0622503 "corr-none"
6.242 0.0517944 "corr-silling"
7.627 0.029021 "lps"
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
0.04983 0.390178
0.3233 0.339095
3.453 0.244481
e
0.05802 0.308139
0.3007 0.196165
3.61 0.0824364
e
0.186 0.533681
0.8852 0.420568
6.256 0.320695
e
0.2067 0.51248
0.965 0.412628
5.592 0.303488
e
0.104 0.0622503
0.9821 0.292488
3.366 0.687491
e
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
e
0.3515 0.384284
1.986 0.276365
24.39 0.216883
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
0.01374 0.466931
0.05029 0.406714
0.5279 0.330688
2.592 0.242284
e
0.02352 0.44057
0.1148 0.342947
1.464 0.238028
6.43 0.104971
e
0.07482 0.145724
1.152 0.146552
e
0.03809 0.375309
0.2734 0.255415
1.287 0.125387
7.627 0.029021
e
0.07793 0.506762
0.4384 0.395818
3.782 0.269266
17.63 0.11095
e
0.3061 0.532192
2.247 0.426641
e
0.02622 0.350017
0.1534 0.292287
1.255 0.177294
6.242 0.0517944
e
0.05166 0.378525
0.2555 0.300901
6.268 0.200412
13.7 0.0563681
e
0.4406 0.336706
0.9813 0.27608
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
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
e
0.1228 0.392877
0.5881 0.264265
4.157 0.206586
e
0.1721 0.367349
0.6894 0.254476
3.259 0.190857
e
0.1198 0.335052
0.9247 0.244522
3.137 0.185088
e
0.1401 0.32135
0.7084 0.263281
3.314 0.162179
e
0.1202 0.34011
0.5423 0.248308
4.249 0.173915
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
0.04983 0.390178
0.3233 0.339095
3.453 0.244481
e
0.186 0.533681
0.8852 0.420568
6.256 0.320695
e
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
e
0.02622 0.350017
0.1534 0.292287
1.255 0.177294
6.242 0.0517944
e
0.05358 0.390168
0.3141 0.339084
3.08 0.244471
e
0.2158 0.533671
0.9167 0.420558
6.202 0.320684
e
0.02456 0.415256
0.1194 0.279532
0.8271 0.217496
e
0.09628 0.415254
0.5427 0.279536
3.124 0.21749
e
0.03186 0.415252
0.1154 0.279541
0.8413 0.217496
e
0.01377 0.350019
0.1032 0.292283
0.7689 0.177295
10.87 0.0517827
e
0.02195 0.350017
0.1528 0.292287
2.126 0.177294
12.15 0.0517944
e
0.02075 0.350019
0.09158 0.292291
0.7228 0.177288
10.93 0.0517919
e
set title 'sweep: connectivity'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
e
0.2751 0.415254
0.5547 0.279536
3.543 0.21749
e
0.3974 0.415654
2.606 0.280186
11.3 0.218248
e
set title 'sweep: solver'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.04983 0.390178
0.3233 0.339095
3.453 0.244481
e
0.1319 0.415254
0.5404 0.279536
4.306 0.21749
e
0.02456 0.415256
0.1194 0.279532
0.8271 0.217496
e
0.008818 0.390178
0.05607 0.339099
0.4002 0.244488
e
unset multiplot
set output
