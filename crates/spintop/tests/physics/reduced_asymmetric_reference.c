// Independent reference for spintop issue 46 F2: a general top under the reduced ALE
// (paper (3.4) with the free motion's Omega', Omega'' in the small terms, kappa = 1):
//   I W' + W x IW = d x { d x (|W|^2 W - W0'') + (d.W0') W + 2 (d.W) W0' }
// and (mode 2) the slow manifold to second order: W' = F2(W), where F2 is one more
// Landau-Lifshitz iteration of (3.4): W'' replaced by DF1(W) F1(W) (central differences),
// W' by F1(W) in the small terms. Stepped by Gragg-Bulirsch-Stoer (fixed order 2K) in
// long double with steps of `turn` radians: h = turn/|W|.
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
typedef long double R;
static R I[3], d[3]; static int mode;
static void cross(const R*a,const R*b,R*c){c[0]=a[1]*b[2]-a[2]*b[1];c[1]=a[2]*b[0]-a[0]*b[2];c[2]=a[0]*b[1]-a[1]*b[0];}
static R dot(const R*a,const R*b){return a[0]*b[0]+a[1]*b[1]+a[2]*b[2];}
static void freeW(const R*W,R*f){R IW[3]={I[0]*W[0],I[1]*W[1],I[2]*W[2]},c[3];cross(W,IW,c);for(int i=0;i<3;i++)f[i]=-c[i]/I[i];}
// small torque with given W' (wd) and W'' (wdd)
static void torque(const R*W,const R*wd,const R*wdd,R*T){
  R W2=dot(W,W),a[3],b[3];
  for(int i=0;i<3;i++) a[i]=W2*W[i]-wdd[i];
  cross(d,a,b);
  R dwd=dot(d,wd), dW=dot(d,W);
  for(int i=0;i<3;i++) b[i]+=dwd*W[i]+2*dW*wd[i];
  cross(d,b,T);
}
static void F1(const R*W,R*f){
  R wd[3],wdd[3],IW[3]={I[0]*W[0],I[1]*W[1],I[2]*W[2]},Iwd[3],c1[3],c2[3],T[3];
  freeW(W,wd); for(int i=0;i<3;i++) Iwd[i]=I[i]*wd[i];
  cross(wd,IW,c1); cross(W,Iwd,c2); for(int i=0;i<3;i++) wdd[i]=-(c1[i]+c2[i])/I[i];
  torque(W,wd,wdd,T); for(int i=0;i<3;i++) f[i]=wd[i]+T[i]/I[i];
}
static void F2(const R*W,R*f){
  R g[3],wdd[3]={0,0,0},T[3],fw[3]; F1(W,g);
  R n=sqrtl(dot(W,W)), h=1e-5L*n;
  for(int j=0;j<3;j++){R Wp[3]={W[0],W[1],W[2]},Wm[3]={W[0],W[1],W[2]},fp[3],fm[3];
    Wp[j]+=h; Wm[j]-=h; F1(Wp,fp); F1(Wm,fm);
    for(int i=0;i<3;i++) wdd[i]+=(fp[i]-fm[i])/(2*h)*g[j];}
  freeW(W,fw); torque(W,g,wdd,T); for(int i=0;i<3;i++) f[i]=fw[i]+T[i]/I[i];
}
static void F(const R*W,R*f){ if(mode==2) F2(W,f); else F1(W,f); }
#define N 3
static int K=6;
static void gbs(R*y,R H){
  static R T[12][12][N]; R f0[N],z0[N],z1[N],fz[N],tmp[N];
  F(y,f0);
  for(int j=0;j<K;j++){int n=2*(j+1); R h=H/n;
    for(int i=0;i<N;i++){z0[i]=y[i]; z1[i]=y[i]+h*f0[i];}
    for(int m=1;m<n;m++){F(z1,fz); for(int i=0;i<N;i++){tmp[i]=z0[i]+2*h*fz[i]; z0[i]=z1[i]; z1[i]=tmp[i];}}
    F(z1,fz); for(int i=0;i<N;i++) T[j][0][i]=(z1[i]+z0[i]+h*fz[i])/2;
    for(int k=1;k<=j;k++){R r=(R)(2*(j+1))/(2*(j-k+1)); r=r*r;
      for(int i=0;i<N;i++) T[j][k][i]=T[j][k-1][i]+(T[j][k-1][i]-T[j-1][k-1][i])/(r-1);}
  }
  for(int i=0;i<N;i++) y[i]=T[K-1][K-1][i];
}
int main(int argc,char**argv){
  // args: mode K turn I1 I2 I3 d1 d2 d3 W1 W2 W3 t1 t2 ...
  mode=atoi(argv[1]); K=atoi(argv[2]); R turn=strtold(argv[3],NULL);
  for(int i=0;i<3;i++){I[i]=strtold(argv[4+i],NULL); d[i]=strtold(argv[7+i],NULL);}
  R y[3]; for(int i=0;i<3;i++) y[i]=strtold(argv[10+i],NULL);
  R t=0; long steps=0;
  for(int a=13;a<argc;a++){R t1=strtold(argv[a],NULL);
    while(t<t1){R h=turn/sqrtl(dot(y,y)); if(t+h>t1) h=t1-t; gbs(y,h); t+=h; steps++;}
    R IW[3]={I[0]*y[0],I[1]*y[1],I[2]*y[2]};
    printf("%s %.21Le %.21Le %.21Le %.21Le %.21Le %ld\n",argv[a],y[0],y[1],y[2],0.5L*dot(y,IW),sqrtl(dot(IW,IW)),steps); fflush(stdout);}
}
